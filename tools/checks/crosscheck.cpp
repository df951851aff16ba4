#include "tools/checks/crosscheck.h"

#include <algorithm>
#include <array>
#include <bit>

#include "core/error.h"
#include "core/footprint.h"
#include "core/input_check.h"
#include "emulated/simt/kernel_fault.h"
#include "reference/float_replay.h"
#include "reference/reference_filter.h"
#include "tools/checks/image_check.h"
#include "tools/checks/rerun_check.h"
#include "tools/checks/table_checker.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf {
namespace {

constexpr std::size_t kFailuresShown = 20;

void Fail(LevelVerdict& verdict, std::string failure) {
  verdict.passed = false;
  if (verdict.failures.size() < kFailuresShown) verdict.failures.push_back(std::move(failure));
}

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

std::string WorkerThreads(int threads) {
  return threads == 0 ? "all cores" : threads == 1 ? "one worker thread" : std::to_string(threads) + " worker threads";
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
                   Defect defect, CrosscheckReport& report, LevelVerdict& tables, LevelVerdict& ideal, LevelVerdict& determinism) {
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

// Level 1: the Vulkan accumulate pass's key words, slot0 and fingerprint for every accepted record equal core's.
void CompareKeys(const RecordBatch& batch, const FilterConfig& config, const HashedRun& run, LevelVerdict& keys) {
  const KeyParams params = MakeKeyParams(config, FootprintScale(config.filter_width_px, batch.fov_y_radians, batch.height),
                                         std::uint32_t(batch.records.size()));
  std::uint64_t compared = 0;
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    if (CheckRecordInputs(batch.records[i]) != InputVerdict::kAccepted) continue;
    const KeyResult expected = shared::ComputeKey(params, batch.records[i]);
    const auto want = KeyResultWords(expected), got = KeyResultWords(run.keys[i]);
    ++compared;
    for (int w = 0; w < int(want.size()); ++w) {
      if (want[w] != got[w]) {
        Fail(keys, "record " + std::to_string(i) + ": " + KeyResultWordName(w) + " differs (core " + std::to_string(want[w]) +
                       ", vulkan " + std::to_string(got[w]) + ")");
        break;
      }
    }
  }
  keys.note = "vulkan accumulate pass against core, word for word: " + std::to_string(compared) + " accepted records compared";
}

void JudgeVulkan(const RecordBatch& batch, const FilterConfig& config, const FilterResult& reference, VulkanFilter& filter,
                 CrosscheckReport& report, LevelVerdict& keys, LevelVerdict& tables, LevelVerdict& ideal, LevelVerdict& determinism) {
  const VulkanRun run = filter.Run(batch, config);
  keys.applicable = true;
  CompareKeys(batch, config, run, keys);
  const std::vector<bool> aliased = JudgeTable("vulkan", batch, run, report, tables);
  const QualityFigures& quality = report.quality.back();
  const bool fixed = config.accumulation == Accumulation::kFixed64;
  Note(ideal, "vulkan", std::string(fixed ? "fixed64: slot sums and counts equal the reference cell's, bit for bit, outside the classified records"
                                          : "float32: counts exact outside the classified records; sums inside the bound at level 2") +
                            CompareWithReference(batch, config, reference, run, aliased, "vulkan: ", ideal));

  const VulkanRun again = filter.Run(batch, config);
  CheckTableOf("vulkan rerun", batch, again, tables);
  JudgeRerun("vulkan", run, again, false, quality, "rerun on the device", determinism);
}

}  // namespace

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

struct Crosschecker::VulkanContext {
  VulkanDevice device;
  VulkanFilter filter;
  std::string description;
  explicit VulkanContext(const VulkanBackendOptions& options)
      : device(options.device_filter, options.staging),
        filter(device, options.accumulate_spv),
        description(device.info().name + ", driver " + device.info().driver_name + " (" + device.info().driver_info +
                    "), memory " + device.info().memory) {}
};

Crosschecker::Crosschecker(const std::vector<std::string>& backends, Defect defect, const VulkanBackendOptions& vulkan)
    : backends_(backends), defect_(defect), vulkan_options_(vulkan) {
  for (const std::string& b : backends_) {
    if (b != "reference" && b != "emulated" && b != "vulkan") {
      throw ConfigError("--backends", "'" + b + "' is not a backend; expected reference, emulated or vulkan");
    }
  }
}

Crosschecker::~Crosschecker() = default;

CrosscheckReport Crosschecker::Check(const RecordBatch& batch, const FilterConfig& config, const EmulatorOptions& emulator) {
  auto has = [&](const char* name) { return std::find(backends_.begin(), backends_.end(), name) != backends_.end(); };
  const bool hashed = has("emulated") || has("vulkan");
  CrosscheckReport report;
  LevelVerdict keys{1, "keys", false, true, "joins with the Vulkan backend; the emulator calls the same core code as the reference", {}};
  LevelVerdict tables{2, "tables", hashed, true, hashed ? "table checker on every hashed backend and its rerun" : "no hashed backend", {}};
  LevelVerdict ideal{3, "agreement with the reference", hashed, true, "", {}};
  LevelVerdict determinism{4, "determinism", hashed, true, "", {}};

  const FilterResult reference = ReferenceFilter(batch, config);
  if (has("emulated")) JudgeEmulated(batch, config, reference, emulator, defect_, report, tables, ideal, determinism);
  if (has("vulkan")) {
    if (!vulkan_) vulkan_ = std::make_unique<VulkanContext>(vulkan_options_);
    report.vulkan_device = vulkan_->description;
    JudgeVulkan(batch, config, reference, vulkan_->filter, report, keys, tables, ideal, determinism);
  }
  report.levels = {keys, tables, ideal, determinism};
  return report;
}

CrosscheckReport Crosscheck(const RecordBatch& batch, const FilterConfig& config, const std::vector<std::string>& backends,
                            const EmulatorOptions& emulator, Defect defect, const VulkanBackendOptions& vulkan) {
  return Crosschecker(backends, defect, vulkan).Check(batch, config, emulator);
}

}  // namespace hpsf
