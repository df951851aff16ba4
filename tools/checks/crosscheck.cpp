#include "tools/checks/crosscheck.h"

#include <algorithm>

#include "core/error.h"
#include "core/footprint.h"
#include "core/input_check.h"
#include "reference/reference_filter.h"
#include "tools/checks/contract_levels.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf {
namespace {

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
                 CrosscheckReport& report, ContractVerdicts& verdicts) {
  LevelVerdict& keys = verdicts.keys;
  LevelVerdict& tables = verdicts.tables;
  LevelVerdict& ideal = verdicts.ideal;
  LevelVerdict& determinism = verdicts.determinism;
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
  ContractVerdicts verdicts(hashed);

  const FilterResult reference = ReferenceFilter(batch, config);
  if (has("emulated")) JudgeEmulated(batch, config, reference, emulator, defect_, report, verdicts);
  if (has("vulkan")) {
    if (!vulkan_) vulkan_ = std::make_unique<VulkanContext>(vulkan_options_);
    report.vulkan_device = vulkan_->description;
    JudgeVulkan(batch, config, reference, vulkan_->filter, report, verdicts);
  }
  report.levels = verdicts.Levels();
  return report;
}

CrosscheckReport Crosscheck(const RecordBatch& batch, const FilterConfig& config, const std::vector<std::string>& backends,
                            const EmulatorOptions& emulator, Defect defect, const VulkanBackendOptions& vulkan) {
  return Crosschecker(backends, defect, vulkan).Check(batch, config, emulator);
}

}  // namespace hpsf
