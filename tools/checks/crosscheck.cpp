#include "tools/checks/crosscheck.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#include "core/error.h"
#include "emulated/simt/kernel_fault.h"
#include "reference/float_replay.h"
#include "reference/reference_filter.h"
#include "tools/checks/table_checker.h"

namespace hpsf {
namespace {

constexpr std::size_t kFailuresShown = 20;

void Fail(LevelVerdict& verdict, std::string failure) {
  verdict.passed = false;
  if (verdict.failures.size() < kFailuresShown) verdict.failures.push_back(std::move(failure));
}

bool SameBits(const Image& a, const Image& b) {
  return a.pixels.size() == b.pixels.size() && std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec3)) == 0;
}

// The quality figures of an emulated run: its probe failures and aliases.
std::vector<bool> Classify(const EmulatedRun& run, QualityFigures& quality) {
  const std::vector<bool> aliased = AliasedSlots(run);
  for (std::size_t i = 0; i < run.placements.size(); ++i) {
    if (run.placements[i] < run.table.capacity && aliased[run.placements[i]]) ++quality.aliased_records;
  }
  quality.aliased_slots = std::uint64_t(std::count(aliased.begin(), aliased.end(), true));
  quality.probe_failures = run.probe_failures;
  return aliased;
}

}  // namespace

bool CrosscheckReport::Passed() const {
  return std::all_of(levels.begin(), levels.end(), [](const LevelVerdict& v) { return !v.applicable || v.passed; });
}

nlohmann::json CrosscheckReport::ToJson() const {
  nlohmann::json j = {{"version", 1}, {"passed", Passed()}};
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

CrosscheckReport Crosscheck(const RecordBatch& batch, const FilterConfig& config, const std::vector<std::string>& backends,
                            const EmulatorOptions& emulator, Defect defect) {
  for (const std::string& b : backends) {
    if (b != "reference" && b != "emulated") {
      throw ConfigError("--backends", "'" + b + "' is not available; this build has: reference, emulated");
    }
  }
  const bool emulated = std::find(backends.begin(), backends.end(), "emulated") != backends.end();
  CrosscheckReport report;
  LevelVerdict keys{1, "keys", false, true, "joins with the Vulkan backend; the emulator calls the same core code as the reference", {}};
  LevelVerdict tables{2, "tables", emulated, true, emulated ? "table checker on every hashed backend" : "no hashed backend", {}};
  LevelVerdict ideal{3, "agreement with the reference", emulated, true, "", {}};
  LevelVerdict determinism{4, "determinism", emulated, true, "", {}};

  const FilterResult reference = ReferenceFilter(batch, config);
  if (emulated) {
    const AccumulateKernelFn kernel = KernelWithDefect(defect);
    EmulatedRun run;
    try {
      run = EmulatedFilter(batch, config, emulator, kernel);
    } catch (const simt::KernelFault& fault) {
      // No table to judge: the kernel wrote outside its buffers, which is itself the defect.
      Fail(tables, std::string("the emulated kernel faulted: ") + fault.what());
      for (LevelVerdict* later : {&ideal, &determinism}) {
        later->applicable = false;
        later->note = "the emulated kernel faulted";
      }
      report.levels = {keys, tables, ideal, determinism};
      return report;
    }
    for (const TableViolation& v : CheckTable({run.table, batch.records, run.keys, run.placements})) Fail(tables, v.ToString());

    QualityFigures quality;
    quality.backend = "emulated";
    const std::vector<bool> aliased = Classify(run, quality);
    report.quality.push_back(quality);

    // Level 3: every record outside the classified ones sits in a slot equal to its reference cell.
    const bool fixed = config.accumulation == Accumulation::kFixed64;
    ideal.note = fixed ? "fixed64: slot sums and counts equal the reference cell's, bit for bit, outside the classified records"
                       : !run.float_add_order.empty()
                           ? "float32: counts exact outside the classified records; each slot's recorded order of adds, replayed by the reference, gives its bits"
                           : "float32: counts exact outside the classified records (fast mode records no order; sums are bounded at level 2)";
    for (std::size_t entry = 0; entry < run.float_add_order.size(); ++entry) {
      const std::uint32_t slot = std::uint32_t(entry / 3);
      const int channel = int(entry % 3);
      const float replayed = ReplayFloatSum(batch.records, run.float_add_order[entry], channel);
      if (std::bit_cast<std::uint32_t>(replayed) != std::bit_cast<std::uint32_t>(run.table.float_sums[slot][channel])) {
        Fail(ideal, "slot " + std::to_string(slot) + " channel " + std::to_string(channel) + ": the replayed order of " +
                        std::to_string(run.float_add_order[entry].size()) + " adds gives other bits");
      }
    }
    std::uint64_t compared = 0;
    for (std::size_t i = 0; i < batch.records.size(); ++i) {
      const std::uint32_t slot = run.placements[i], cell = reference.placement[i];
      const bool classified = slot == kProbeFailure || (slot < run.table.capacity && aliased[slot]);
      if (classified) continue;
      if ((slot < run.table.capacity) != (cell != kNoCell)) {
        Fail(ideal, "record " + std::to_string(i) + ": placed in the table but not in the reference, or the other way round");
        continue;
      }
      if (cell == kNoCell) continue;
      ++compared;
      const TableCell& c = reference.cells[cell];
      if (run.table.counts[slot] != c.count) {
        Fail(ideal, "record " + std::to_string(i) + " at slot " + std::to_string(slot) + ": count " + std::to_string(run.table.counts[slot]) +
                        ", reference " + std::to_string(c.count));
      } else if (fixed && run.table.fixed_sums[slot] != c.fixed_sum) {
        Fail(ideal, "record " + std::to_string(i) + " at slot " + std::to_string(slot) + ": sums differ from the reference cell's");
      }
    }
    ideal.note += "; " + std::to_string(compared) + " records compared";
    if (fixed && quality.probe_failures == 0 && quality.aliased_slots == 0 && !SameBits(run.image, reference.image)) {
      Fail(ideal, "nothing failed or aliased, yet the image differs from the reference");
    }

    // Level 4: the same inputs again give the same bits (and, faithfully, the same trace).
    const EmulatedRun again = EmulatedFilter(batch, config, emulator, kernel);
    if (emulator.mode == simt::Mode::kFaithful) {
      determinism.note = "faithful rerun: same trace hash and image";
      if (again.launch.trace_hash != run.launch.trace_hash) Fail(determinism, "the trace hash changed between two identical runs");
      if (!SameBits(again.image, run.image)) Fail(determinism, "the image changed between two identical runs");
    } else if (quality.probe_failures == 0 && quality.aliased_slots == 0) {
      determinism.note = "fast rerun with nothing failed or aliased: same image";
      if (!SameBits(again.image, run.image)) Fail(determinism, "the image changed between two identical fast runs");
    } else {
      determinism.applicable = false;
      determinism.note = "fast mode with probe failures or aliases: which records fail depends on thread timing";
    }
  }
  report.levels = {keys, tables, ideal, determinism};
  return report;
}

}  // namespace hpsf
