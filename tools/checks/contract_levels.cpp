#include "tools/checks/contract_levels.h"

#include <algorithm>
#include <bit>

#include "emulated/simt/kernel_fault.h"
#include "reference/float_replay.h"
#include "reference/reference_filter.h"
#include "tools/checks/image_check.h"
#include "tools/checks/rerun_check.h"
#include "tools/checks/table_checker.h"

namespace hpsf {
namespace {

constexpr std::size_t kFailuresShown = 20;

// The quality figures of a hashed run: its probe failures and aliases.
std::vector<bool> Classify(const HashedRun& run, QualityFigures& quality) {
  const std::vector<bool> aliased = AliasedSlots(run);
  for (std::size_t i = 0; i < run.placements.size(); ++i) {
    if (run.placements[i] < run.table.capacity && aliased[run.placements[i]]) ++quality.aliased_records;
  }
  quality.aliased_slots = std::uint64_t(std::count(aliased.begin(), aliased.end(), true));
  quality.probe_failures = run.probe_failures;
  return aliased;
}

std::string WorkerThreads(int threads) {
  return threads == 0 ? "all cores" : threads == 1 ? "one worker thread" : std::to_string(threads) + " worker threads";
}

}  // namespace

ContractVerdicts::ContractVerdicts(bool hashed)
    : keys{1, "keys", false, true, "joins with the Vulkan backend; the emulator calls the same core code as the reference", {}},
      tables{2, "tables", hashed, true, hashed ? "table checker on every hashed backend and its rerun" : "no hashed backend", {}},
      ideal{3, "agreement with the reference", hashed, true, "", {}},
      determinism{4, "determinism", hashed, true, "", {}} {}


void Fail(LevelVerdict& verdict, std::string failure) {
  verdict.passed = false;
  if (verdict.failures.size() < kFailuresShown) verdict.failures.push_back(std::move(failure));
}

// Level 3 for one hashed run: every record outside the classified ones (probe failures, aliased slots) sits
// in a slot whose count, and in fixed64 whose sums, equal its reference cell's; with nothing classified in
// fixed64, the image is the reference's, bit for bit; and every image is the resolve of its own table.
// Returns what was compared, for the verdict's note.
std::string CompareWithReference(const RecordBatch& batch, const FilterConfig& config, const FilterResult& reference, const HashedRun& run,
                                 const std::vector<bool>& aliased, const std::string& prefix, LevelVerdict& ideal) {
  const bool fixed = config.accumulation == Accumulation::kFixed64;
  std::uint64_t compared = 0, failures = 0;
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    const std::uint32_t slot = run.placements[i], cell = reference.placement[i];
    failures += slot == kProbeFailure;
    const bool classified = slot == kProbeFailure || (slot < run.table.capacity && aliased[slot]);
    if (classified) continue;
    if ((slot < run.table.capacity) != (cell != kNoCell)) {
      Fail(ideal, prefix + "record " + std::to_string(i) + ": placed in the table but not in the reference, or the other way round");
      continue;
    }
    if (cell == kNoCell) continue;
    ++compared;
    const TableCell& c = reference.cells[cell];
    if (run.table.counts[slot] != c.count) {
      Fail(ideal, prefix + "record " + std::to_string(i) + " at slot " + std::to_string(slot) + ": count " + std::to_string(run.table.counts[slot]) +
                      ", reference " + std::to_string(c.count));
    } else if (fixed && run.table.fixed_sums[slot] != c.fixed_sum) {
      Fail(ideal, prefix + "record " + std::to_string(i) + " at slot " + std::to_string(slot) + ": sums differ from the reference cell's");
    }
  }
  if (fixed && failures == 0 && std::count(aliased.begin(), aliased.end(), true) == 0 && !SameBits(run.image, reference.image)) {
    Fail(ideal, prefix + "nothing failed or aliased, yet the image differs from the reference");
  }
  // Every image, classified records included, is the resolve of its own table: bit for bit in fixed64, within
  // the float32 bound of the exact sums.
  for (const std::string& pixel : CheckImageAgainstTable(batch, run)) Fail(ideal, prefix + "image: " + pixel);
  return "; " + std::to_string(compared) + " records compared; image " +
         (fixed ? "equals the resolve of its table" : "within the float32 bound of its table's exact resolve");
}

// A verdict's note gathers what each backend contributed to it.
void Note(LevelVerdict& verdict, const std::string& backend, const std::string& text) {
  verdict.note += (verdict.note.empty() ? "" : " | ") + backend + ": " + text;
}

void CheckTableOf(const std::string& backend, const RecordBatch& batch, const HashedRun& run, LevelVerdict& tables) {
  for (const TableViolation& v : CheckTable({run.table, batch.records, run.keys, run.placements})) Fail(tables, backend + ": " + v.ToString());
}

// Level 2 for one hashed run, and its quality figures; returns which slots aliased.
std::vector<bool> JudgeTable(const std::string& backend, const RecordBatch& batch, const HashedRun& run, CrosscheckReport& report,
                             LevelVerdict& tables) {
  CheckTableOf(backend, batch, run, tables);
  QualityFigures quality;
  quality.backend = backend;
  const std::vector<bool> aliased = Classify(run, quality);
  report.quality.push_back(quality);
  return aliased;
}

// Level 4 for one hashed backend: the rerun is compared in what the contract promises for its kind of run, and
// no further (DESIGN.md: no output bit depends on timing except where the contract classifies it).
void JudgeRerun(const std::string& backend, const HashedRun& first, const HashedRun& second, bool ordered,
                const QualityFigures& quality, const std::string& how, LevelVerdict& determinism) {
  QualityFigures rerun;
  Classify(second, rerun);
  const bool failed_or_aliased = quality.probe_failures + quality.aliased_slots + rerun.probe_failures + rerun.aliased_slots > 0;
  const RerunPromise promise = RerunPromiseFor(ordered, first.table.accumulation, failed_or_aliased);
  Note(determinism, backend, how + "; promised: " + ToString(promise));
  for (const std::string& difference : CompareReruns(first, second, promise)) Fail(determinism, backend + ": " + difference);
}

void JudgeEmulated(const RecordBatch& batch, const FilterConfig& config, const FilterResult& reference, const EmulatorOptions& emulator,
                   Defect defect, CrosscheckReport& report, ContractVerdicts& verdicts) {
  LevelVerdict& tables = verdicts.tables;
  LevelVerdict& ideal = verdicts.ideal;
  LevelVerdict& determinism = verdicts.determinism;
  const AccumulateKernelFn kernel = KernelWithDefect(defect);
  EmulatedRun run;
  try {
    run = EmulatedFilter(batch, config, emulator, kernel);
  } catch (const simt::KernelFault& fault) {
    // No table to judge: the kernel wrote outside its buffers, which is itself the defect.
    Fail(tables, std::string("emulated: the kernel faulted: ") + fault.what());
    Note(ideal, "emulated", "not judged, the kernel faulted");
    Note(determinism, "emulated", "not judged, the kernel faulted");
    return;
  }
  const std::vector<bool> aliased = JudgeTable("emulated", batch, run, report, tables);
  const QualityFigures& quality = report.quality.back();

  // Level 3: every record outside the classified ones sits in a slot equal to its reference cell.
  const bool fixed = config.accumulation == Accumulation::kFixed64;
  std::string note = fixed ? "fixed64: slot sums and counts equal the reference cell's, bit for bit, outside the classified records"
                     : !run.float_add_order.empty()
                         ? "float32: counts exact outside the classified records; each slot's recorded order of adds, replayed by the reference, gives its bits"
                         : "float32: counts exact outside the classified records (fast mode records no order; sums are bounded at level 2)";
  for (std::size_t entry = 0; entry < run.float_add_order.size(); ++entry) {
    const std::uint32_t slot = std::uint32_t(entry / 3);
    const int channel = int(entry % 3);
    const float replayed = ReplayFloatSum(batch.records, run.float_add_order[entry], channel);
    if (std::bit_cast<std::uint32_t>(replayed) != std::bit_cast<std::uint32_t>(run.table.float_sums[slot][channel])) {
      Fail(ideal, "emulated: slot " + std::to_string(slot) + " channel " + std::to_string(channel) + ": the replayed order of " +
                      std::to_string(run.float_add_order[entry].size()) + " adds gives other bits");
    }
  }
  Note(ideal, "emulated", note + CompareWithReference(batch, config, reference, run, aliased, "emulated: ", ideal));

  // Level 4: a rerun keeps what the contract promises; in fast mode it runs on another number of worker threads,
  // since no promised bit may depend on it. The rerun's table is judged at level 2 too.
  EmulatorOptions rerun_options = emulator;
  if (emulator.mode == simt::Mode::kFast) rerun_options.threads = emulator.threads == 1 ? 0 : 1;
  EmulatedRun again;
  try {
    again = EmulatedFilter(batch, config, rerun_options, kernel);
  } catch (const simt::KernelFault& fault) {
    Fail(tables, std::string("emulated rerun: the kernel faulted: ") + fault.what());
    Note(determinism, "emulated", "not judged, the rerun's kernel faulted");
    return;
  }
  CheckTableOf("emulated rerun", batch, again, tables);
  const bool ordered = emulator.mode == simt::Mode::kFaithful;
  if (ordered && again.launch.trace_hash != run.launch.trace_hash) {
    Fail(determinism, "emulated: the trace hash changed between two identical runs");
  }
  const std::string how = ordered ? "faithful rerun" : "fast rerun with " + WorkerThreads(rerun_options.threads);
  JudgeRerun("emulated", run, again, ordered, quality, how, determinism);
}


CrosscheckReport CrosscheckEmulated(const RecordBatch& batch, const FilterConfig& config, const EmulatorOptions& emulator, Defect defect) {
  CrosscheckReport report;
  ContractVerdicts verdicts(true);
  JudgeEmulated(batch, config, ReferenceFilter(batch, config), emulator, defect, report, verdicts);
  report.levels = verdicts.Levels();
  return report;
}

bool CrosscheckReport::Passed() const {
  return std::all_of(levels.begin(), levels.end(), [](const LevelVerdict& v) { return !v.applicable || v.passed; });
}

nlohmann::json CrosscheckReport::ToJson() const {
  nlohmann::json j = {{"version", 2}, {"passed", Passed()}};
  if (!vulkan_device.empty()) j["vulkan_device"] = vulkan_device;
  for (const LevelVerdict& v : levels) {
    j["levels"].push_back({{"level", v.level}, {"name", v.name}, {"applicable", v.applicable}, {"passed", v.passed},
                           {"note", v.note}, {"failures", v.failures}});
  }
  for (const QualityFigures& q : quality) {
    j["quality"].push_back({{"backend", q.backend}, {"probe_failures", q.probe_failures}, {"aliased_slots", q.aliased_slots},
                            {"aliased_records", q.aliased_records}});
  }
  return j;
}

}  // namespace hpsf
