#include "verifier/contract/contract_levels.h"

#include <bit>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "core/footprint.h"
#include "core/input_check.h"
#include "core/read_back_check.h"
#include "emulated/simt/kernel_fault.h"
#include "reference/float_replay.h"
#include "reference/reference_backend.h"
#include "verifier/checker/classified_slots.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/given_keys.h"
#include "verifier/contract/image_check.h"
#include "verifier/contract/rerun_check.h"
#include "verifier/contract/search_check.h"
#include "verifier/contract/transport_check.h"

namespace hpsf {
namespace {

// A verdict's note gathers what each backend contributed to it.
void Note(LevelVerdict& verdict, const std::string& backend, const std::string& text) {
  verdict.note += (verdict.note.empty() ? "" : " | ") + backend + ": " + text;
}

std::string WorkerThreads(int threads) {
  return threads == 0 ? "all cores" : threads == 1 ? "one worker thread" : std::to_string(threads) + " worker threads";
}

// Level 1: the backend's key words, slot0 and fingerprint for every accepted record (the records then the deeper
// ones) equal core's. Returns how many records were compared.
std::uint64_t CompareKeys(const RecordBatch& batch, const FilterConfig& config, std::span<const KeyResult> backend_keys,
                          const std::string& prefix, LevelVerdict& keys) {
  const KeyParams params =
      MakeKeyParams(config, FootprintScale(config.filter_width_px, batch.fov_y_radians, batch.height),
                    std::uint32_t(batch.records.size()));
  const TableRecords records(batch);
  std::uint64_t compared = 0;
  if (backend_keys.size() != records.size()) {
    keys.Fail(prefix + std::to_string(backend_keys.size()) + " keys for " + std::to_string(records.size()) +
              " records");
    return compared;
  }
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (CheckRecordInputs(records.all()[i]) != InputVerdict::kAccepted) continue;
    const KeyResult expected = shared::ComputeKey(params, records.all()[i]);
    const auto want = KeyResultWords(expected), got = KeyResultWords(backend_keys[i]);
    ++compared;
    for (int w = 0; w < int(want.size()); ++w) {
      if (want[w] != got[w]) {
        keys.Fail(prefix + "record " + std::to_string(i) + ": " + KeyResultWordName(w) + " differs (core " +
                  std::to_string(want[w]) + ", backend " + std::to_string(got[w]) + ")");
        break;
      }
    }
  }
  return compared;
}

// Level 2: the table checker on one frame of a hashed run, from the table before it. records: what the frame added
// (JudgeTransportReads': the records then the deeper ones, transported from the table before).
void CheckFrameTable(const std::string& who, std::span<const Record> records, const HashedRun& run,
                     const std::optional<HashTableDump>& before, const FilterConfig& config, LevelVerdict& tables) {
  TableCheckInput input{run.table, records, run.keys, run.placements};
  input.coarser_placements = run.coarser_placements;
  input.before = before ? &*before : nullptr;
  input.eviction = config.eviction;
  input.frame = config.frame;
  input.temporal = config.temporal;
  input.level_seed = config.level_seed;
  input.normal_in_index = config.normal_in_index;
  for (const TableViolation& v : CheckTable(input)) tables.Fail(who + ": " + v.ToString());
}

// Level 3 for one frame of a hashed run: every record (the records then the deeper ones) outside the classified
// slots (probe failures, aliases, cells that failed before or were fed from classified reads) sits in a slot whose
// count, and in fixed64 whose sums, equal its reference cell's; with nothing classified in fixed64, the image is the
// reference's, bit for bit; and every image is the resolve of its own table. Returns how many records were compared.
std::uint64_t CompareWithReference(const RecordBatch& batch, const FilterConfig& config, const FilterResult& reference,
                                   const HashedRun& run, const HashTableDump* before,
                                   const std::vector<bool>& classified, std::uint64_t classified_reads,
                                   const std::string& prefix, LevelVerdict& ideal) {
  const bool fixed = IntegerSums(config.accumulation);  // fixed64 or packed-decimal: exact
  std::uint64_t compared = 0, failures = 0;
  // Each level of a record in turn (core/shared/levels.h): its own cell, then the coarser ones.
  const std::size_t n = batch.records.size() + batch.deeper.size();
  for (std::size_t touch = 0; touch < n * run.table.levels; ++touch) {
    const std::size_t i = touch % n;
    const std::uint32_t k = std::uint32_t(touch / n);
    const std::uint32_t slot = LevelPlacement(run, i, k);
    const std::size_t at = std::size_t(k - 1) * n + i;
    const std::uint32_t cell = k == 0                                    ? reference.placement[i]
                               : at < reference.coarser_placement.size() ? reference.coarser_placement[at]
                                                                         : kNoCell;
    const std::string record = "record " + std::to_string(i) + (k > 0 ? " (" + std::to_string(k) + " levels up)" : "");
    failures += slot == kProbeFailure;
    if (slot == kProbeFailure || (slot < run.table.capacity && classified[slot])) continue;
    if ((slot < run.table.capacity) != (cell != kNoCell)) {
      ideal.Fail(prefix + record + ": placed in the table but not in the reference, or the other way round");
      continue;
    }
    if (cell == kNoCell) continue;
    ++compared;
    const TableCell& c = reference.cells[cell];
    // The adaptive blend's count follows the cell's float averages, whose rounding follows the order of float adds:
    // a float32 slot with a history is held to the checker's count bounds (level 2), not to the reference's count.
    const bool adaptive_float_history = !fixed && config.temporal.adapts() && before && before->counts[slot] != 0;
    if (adaptive_float_history) continue;
    if (run.table.counts[slot] != c.count) {
      ideal.Fail(prefix + record + " at slot " + std::to_string(slot) + ": count " +
                 std::to_string(run.table.counts[slot]) + ", reference " + std::to_string(c.count));
    } else if (fixed && run.table.fixed_sums[slot] != c.fixed_sum) {
      ideal.Fail(prefix + record + " at slot " + std::to_string(slot) + ": sums differ from the reference cell's");
    } else if (fixed && config.second_moments &&
               (!run.table.second_moments || run.table.fixed_squares.size() <= slot ||
                run.table.fixed_squares[slot] != c.fixed_square)) {
      ideal.Fail(prefix + record + " at slot " + std::to_string(slot) +
                 ": square sum differs from the reference cell's");
    } else if (!run.table.frame_counters.empty() && run.table.frame_counters[slot] != c.frames) {
      ideal.Fail(prefix + record + " at slot " + std::to_string(slot) + ": frame counter " +
                 std::to_string(run.table.frame_counters[slot]) + ", reference " + std::to_string(c.frames));
    }
  }
  if (fixed && failures == 0 && std::count(classified.begin(), classified.end(), true) == 0 && classified_reads == 0 &&
      !SameBits(run.image, reference.image)) {
    ideal.Fail(prefix + "nothing failed or aliased, yet the image differs from the reference");
  }
  // Every image, classified records included, is the resolve of its own table: bit for bit in fixed64, within
  // the float32 bound of the exact sums.
  for (const std::string& pixel : CheckImageAgainstTable(batch, run, before)) ideal.Fail(prefix + "image: " + pixel);
  return compared;
}

// Level 3, the faithful emulator in float32: each slot's recorded order of adds of `records` (what the frame added),
// replayed by the reference, gives its bits, for every slot that held nothing before the frame (a sum carried over
// starts elsewhere).
void CompareFloatOrder(std::span<const Record> records, const HashedRun& run,
                       const std::optional<HashTableDump>& before, const std::string& prefix, LevelVerdict& ideal) {
  for (std::size_t entry = 0; entry < run.float_add_order.size(); ++entry) {
    const std::uint32_t slot = std::uint32_t(entry / 3);
    const int channel = int(entry % 3);
    if (before && before->counts[slot] != 0) continue;
    if (!run.seeded_slots.empty() && run.seeded_slots[slot]) continue;  // its seed was added after the frame's adds
    const float replayed = ReplayFloatSum(records, run.float_add_order[entry], channel);
    if (std::bit_cast<std::uint32_t>(replayed) != std::bit_cast<std::uint32_t>(run.table.float_sums[slot][channel])) {
      ideal.Fail(prefix + "slot " + std::to_string(slot) + " channel " + std::to_string(channel) +
                 ": the replayed order of " + std::to_string(run.float_add_order[entry].size()) +
                 " adds gives other bits");
    }
  }
}

// Filters one frame; a kernel that writes outside its buffers faults, and a shader whose output words cannot be
// used (core/read_back_check.h) is refused: either is itself the defect, with no table to judge. The refused
// run's key results, values only, go to `refused_keys` for level 1.
const HashedRun* FilterOrFault(Backend& backend, const RecordBatch& batch, const FilterConfig& config,
                               const std::string& who, LevelVerdict& tables,
                               std::vector<KeyResult>* refused_keys = nullptr) {
  try {
    backend.FilterFrame(batch, config);
    return backend.LastHashedRun();
  } catch (const simt::KernelFault& fault) {
    tables.Fail(who + ": the kernel faulted: " + fault.what());
  } catch (const ShaderOutputError& error) {
    for (const std::string& fault : error.faults()) tables.Fail(who + ": invalid shader output: " + fault);
    if (refused_keys && error.keys().size() == batch.records.size()) *refused_keys = error.keys();
  }
  return nullptr;
}

// What the contract judged of one hashed backend over the sequence.
struct SequenceState {
  SequenceState(bool evicts_under_pressure, bool seeds_levels, bool normal_in_index)
      : classes(evicts_under_pressure, seeds_levels, normal_in_index),
        rerun_classes(evicts_under_pressure, seeds_levels, normal_in_index) {}
  ClassifiedSlots classes, rerun_classes;
  std::optional<HashTableDump> before, rerun_before;  // the tables before this frame
  QualityFigures quality;
  std::uint64_t keys_compared = 0, records_compared = 0;
  bool replayed_float_order = false;
  bool lookup_aliased = false;  // a search's lookup read another cell, in the run or its rerun, in some frame
  std::set<std::string> promises;
  bool faulted = false;
  std::string fault_at;  // " from frame N on", in a sequence
};

}  // namespace

EmulatedPair::EmulatedPair(const EmulatorOptions& emulator, Defect defect)
    : options_(emulator),
      backend_(WithDefect(emulator, defect), KernelWithDefect(defect)),
      rerun_(WithDefect(RerunOptions(emulator), defect), KernelWithDefect(defect)) {}

EmulatorOptions EmulatedPair::RerunOptions(const EmulatorOptions& emulator) {
  EmulatorOptions rerun = emulator;
  if (emulator.mode == simt::Mode::kFast) rerun.threads = emulator.threads == 1 ? 0 : 1;
  return rerun;
}

JudgedBackend EmulatedPair::Judged() {
  const bool ordered = options_.mode == simt::Mode::kFaithful;
  const std::string how =
      ordered ? "faithful rerun" : "fast rerun with " + WorkerThreads(RerunOptions(options_).threads);
  return {"emulated", &backend_, &rerun_, how, ordered, false};
}

CrosscheckReport JudgeSequence(std::span<const RecordBatch> frames, std::span<const std::uint32_t> numbers,
                               FilterConfig config, std::span<const JudgedBackend> hashed,
                               const FrameObserver& observer) {
  const bool any_hashed = !hashed.empty();
  const bool several = frames.size() > 1;
  const bool fixed = IntegerSums(config.accumulation);
  LevelVerdict keys{1, "keys", false, true, "", {}};
  LevelVerdict tables{2, "tables", any_hashed, true, "", {}};
  LevelVerdict ideal{3, "agreement with the reference", any_hashed, true, "", {}};
  LevelVerdict determinism{4, "determinism", any_hashed, true, "", {}};
  ReferenceBackend reference;
  std::vector<SequenceState> states;
  for (std::size_t b = 0; b < hashed.size(); ++b) {
    states.emplace_back(config.eviction.by_priority(), config.level_seed.enabled, config.normal_in_index);
    hashed[b].backend->Reset();
    hashed[b].rerun->Reset();
    states[b].quality.backend = hashed[b].name;
  }
  for (std::size_t k = 0; k < frames.size(); ++k) {
    config.frame = numbers[k];
    const RecordBatch& batch = frames[k];
    reference.FilterFrame(batch, config);
    const int fixed_point_bits = reference.result().stats.fixed_point_bits;
    for (std::size_t b = 0; b < hashed.size(); ++b) {
      const JudgedBackend& judged = hashed[b];
      SequenceState& s = states[b];
      if (s.faulted) continue;
      const std::string who = several ? judged.name + ", frame " + std::to_string(numbers[k]) : judged.name;
      std::vector<KeyResult> refused_keys;
      const HashedRun* run = FilterOrFault(*judged.backend, batch, config, who, tables, &refused_keys);
      const HashedRun* again = run ? FilterOrFault(*judged.rerun, batch, config, who + " rerun", tables) : nullptr;
      if (judged.judge_keys && !judged.shader_keys && !refused_keys.empty()) {
        s.keys_compared += CompareKeys(batch, config, refused_keys, who + ": ", keys);
      }
      if (!run || !again) {
        s.faulted = true;
        s.fault_at = several ? " from frame " + std::to_string(numbers[k]) + " on" : "";
        continue;
      }
      if (observer) observer(judged.name, batch, numbers[k], *run, s.before ? &*s.before : nullptr);
      if (judged.shader_keys) {
        s.keys_compared += JudgeGivenKeys(run->keys, batch.records, run->table.capacity, config, who + ": ", keys);
      } else if (judged.judge_keys) {
        s.keys_compared += CompareKeys(batch, config, run->keys, who + ": ", keys);
      }
      if (run->table.fixed_point_bits != fixed_point_bits) {
        tables.Fail(who + ": F " + std::to_string(run->table.fixed_point_bits) + ", the reference's " +
                    std::to_string(fixed_point_bits) + ": sums of different scales cannot be compared");
      }

      const HashTableDump* before = s.before ? &*s.before : nullptr;
      // What the frame added to each table: the records then the deeper ones, transported from the table before.
      const RecordBatch added = JudgeTransportReads(batch, config, before, *run, who + ": ", tables);
      const RecordBatch rerun_added = JudgeTransportReads(batch, config, s.rerun_before ? &*s.rerun_before : nullptr,
                                                          *again, who + " rerun: ", tables);
      const TableRecords added_records(added), rerun_added_records(rerun_added);
      CheckFrameTable(who, added_records.all(), *run, s.before, config, tables);
      CheckFrameTable(who + " rerun", rerun_added_records.all(), *again, s.rerun_before, config, tables);

      // The transports judged against the classes of the tables before the frame, which they read.
      const TransportComparison transports =
          CompareTransports(batch, config, reference.result(), *run, s.classes, who + ": ", ideal);
      LevelVerdict rerun_transports;
      const TransportComparison rerun_fed =
          CompareTransports(batch, config, reference.result(), *again, s.rerun_classes, "", rerun_transports);
      s.quality.classified_transports += transports.classified;
      const std::vector<bool>& classified = s.classes.AddFrame(*run, transports.fed);
      const std::vector<bool>& rerun_classified = s.rerun_classes.AddFrame(*again, rerun_fed.fed);
      s.quality.probe_failures += run->probe_failures;
      s.quality.aliased_slots += s.classes.aliased_slots();
      s.quality.aliased_records += s.classes.classified_records();

      if (!run->float_add_order.empty()) {
        s.replayed_float_order = true;
        CompareFloatOrder(added_records.all(), *run, s.before, who + ": ", ideal);
      }
      if (judged.shader_keys) {  // the reference's cells are hpsf's keys; these records' cells are the shader's
        s.records_compared += CompareWithExactMap(added.records, *run, s.before ? &*s.before : nullptr, classified,
                                                  config, who + ": ", ideal);
        for (const std::string& pixel : CheckImageAgainstTable(added, *run, s.before ? &*s.before : nullptr)) {
          ideal.Fail(who + ": image: " + pixel);
        }
      } else {
        const SearchComparison searches =
            CompareSearches(added, reference.result(), *run, s.classes, classified, who + ": ", ideal);
        s.quality.classified_searches += searches.classified;
        // The rerun's own lookups, for level 4's promise: its differences from the reference are not level 3's.
        LevelVerdict rerun_searches;
        s.lookup_aliased =
            s.lookup_aliased || searches.classified > 0 ||
            CompareSearches(added, reference.result(), *again, s.rerun_classes, rerun_classified, "", rerun_searches)
                    .classified > 0;
        s.records_compared += CompareWithReference(added, config, reference.result(), *run, before, classified,
                                                   searches.classified + transports.classified, who + ": ", ideal);
      }

      if (judged.ordered && again->trace_hash != run->trace_hash) {
        determinism.Fail(who + ": the trace hash changed between two identical runs");
      }
      const RerunPromise promise = RerunPromiseFor(judged.ordered, config.accumulation,
                                                   s.classes.any() || s.rerun_classes.any(), s.lookup_aliased);
      s.promises.insert(ToString(promise));
      for (const std::string& difference : CompareReruns(*run, *again, promise)) {
        determinism.Fail(who + ": " + difference);
      }
      if (k + 1 < frames.size()) {
        s.before = run->table;
        s.rerun_before = again->table;
      }
    }
  }

  const std::string over = several ? " over " + std::to_string(frames.size()) + " frames" : "";
  keys.note = "joins with the Vulkan backend; the emulator calls the same core code as the reference";
  tables.note = any_hashed ? "table checker on every hashed backend and its rerun" +
                                 std::string(several ? ", each frame from the table before it" : "")
                           : "no hashed backend";
  CrosscheckReport report;
  report.fixed_point_bits = frames.empty() ? 0 : reference.result().stats.fixed_point_bits;
  report.accumulation = config.accumulation;
  if (config.second_moments && !frames.empty()) report.square_bits = reference.result().stats.square_bits;
  for (std::size_t b = 0; b < hashed.size(); ++b) {
    const JudgedBackend& judged = hashed[b];
    const SequenceState& s = states[b];
    report.quality.push_back(s.quality);
    if (judged.shader_keys) {
      keys.applicable = true;
      keys.note = judged.name + "'s own keys (--key-source shader): home slot, identity, one key per cell: " +
                  std::to_string(s.keys_compared) + " keyed records judged" + over;
    } else if (judged.judge_keys) {
      keys.applicable = true;
      keys.note = judged.name + " against core, word for word: " + std::to_string(s.keys_compared) +
                  " accepted records compared" + over;
    }
    if (s.faulted) {
      Note(ideal, judged.name, "not judged" + s.fault_at + ", the kernel faulted or its output was invalid");
      Note(determinism, judged.name, "not judged" + s.fault_at + ", the kernel faulted or its output was invalid");
      continue;
    }
    const std::string sums =
        fixed ? ToString(config.accumulation) +
                    ": slot sums and counts equal the reference cell's, bit for bit, outside the classified records"
              : std::string("float32: counts exact outside the classified records") +
                    (config.temporal.adapts() ? " (adaptive: a slot with a history within level 2's bounds); " : "; ") +
                    (s.replayed_float_order
                         ? "each new slot's recorded order of adds, replayed by the reference, gives its bits"
                         : "sums inside the bound at level 2");
    const std::string against =
        judged.shader_keys ? "the exact map over the shader's own key words (no reference image: its cells are not "
                             "hpsf's): "
                           : "";
    Note(ideal, judged.name,
         against + sums + "; " + std::to_string(s.records_compared) + " records compared" + over + "; image " +
             (fixed ? "equals the resolve of its table" : "within the float32 bound of its table's exact resolve"));
    std::string promised;
    for (const std::string& p : s.promises) promised += (promised.empty() ? "" : ", ") + p;
    Note(determinism, judged.name, judged.rerun_how + "; promised: " + promised);
  }
  report.levels = {keys, tables, ideal, determinism};
  report.frames = std::uint32_t(frames.size());
  return report;
}

CrosscheckReport CrosscheckEmulated(const RecordBatch& batch, const FilterConfig& config,
                                    const EmulatorOptions& emulator, Defect defect) {
  EmulatedPair emulated(emulator, defect);
  const JudgedBackend judged = emulated.Judged();
  return JudgeSequence(std::span<const RecordBatch>(&batch, 1), std::span<const std::uint32_t>(&config.frame, 1),
                       config, std::span<const JudgedBackend>(&judged, 1));
}

CrosscheckReport CrosscheckEmulatedSequence(std::span<const RecordBatch> frames, const FilterConfig& config,
                                            const EmulatorOptions& emulator) {
  EmulatedPair emulated(emulator, Defect::kNone);
  const JudgedBackend judged = emulated.Judged();
  std::vector<std::uint32_t> numbers;
  for (const RecordBatch& batch : frames) numbers.push_back(batch.frame);
  return JudgeSequence(frames, numbers, config, std::span<const JudgedBackend>(&judged, 1));
}

bool CrosscheckReport::Passed() const {
  return std::all_of(levels.begin(), levels.end(), [](const LevelVerdict& v) { return !v.applicable || v.passed; });
}

std::string CrosscheckReport::FirstFailure() const {
  for (const LevelVerdict& v : levels) {
    if (v.applicable && !v.passed) {
      return "level " + std::to_string(v.level) + " " + v.name + ": " + (v.failures.empty() ? v.note : v.failures[0]);
    }
  }
  return "";
}

nlohmann::json CrosscheckReport::ToJson() const {
  nlohmann::json j = {{"version", 2},
                      {"passed", Passed()},
                      {"frames", frames},
                      {"accumulation", ToString(accumulation)},
                      {"fixed_point_bits", fixed_point_bits}};
  if (!vulkan_device.empty()) j["vulkan_device"] = vulkan_device;
  if (square_bits) j["square_bits"] = *square_bits;
  for (const LevelVerdict& v : levels) {
    j["levels"].push_back({{"level", v.level},
                           {"name", v.name},
                           {"applicable", v.applicable},
                           {"passed", v.passed},
                           {"note", v.note},
                           {"failures", v.failures}});
  }
  for (const QualityFigures& q : quality) {
    j["quality"].push_back({{"backend", q.backend},
                            {"probe_failures", q.probe_failures},
                            {"aliased_slots", q.aliased_slots},
                            {"aliased_records", q.aliased_records},
                            {"classified_searches", q.classified_searches},
                            {"classified_transports", q.classified_transports}});
  }
  return j;
}

std::string CrosscheckReport::ToText() const {
  std::ostringstream out;
  for (const LevelVerdict& v : levels) {
    out << "level " << v.level << " " << v.name << ": "
        << (!v.applicable ? "n/a"
            : v.passed    ? "PASS"
                          : "FAIL")
        << " (" << v.note << ")\n";
    for (const std::string& f : v.failures) out << "  " << f << "\n";
  }
  if (frames > 1) out << "frames: " << frames << ", each judged from the table before it\n";
  out << "accumulation: " << ToString(accumulation) << ", F " << fixed_point_bits << " fraction bits"
      << (square_bits ? ", second moments at G " + std::to_string(*square_bits) : std::string()) << "\n";
  if (!vulkan_device.empty()) out << "vulkan device: " << vulkan_device << "\n";
  for (const QualityFigures& q : quality) {
    out << q.backend << ": probe failures " << q.probe_failures << ", aliased slots " << q.aliased_slots
        << ", records in aliased slots " << q.aliased_records
        << (q.classified_searches > 0 ? ", searches classified " + std::to_string(q.classified_searches) : "")
        << (q.classified_transports > 0 ? ", transports classified " + std::to_string(q.classified_transports) : "")
        << "\n";
  }
  return out.str();
}

}  // namespace hpsf
