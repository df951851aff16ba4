// The repro bundle a failed check leaves behind (DESIGN.md, "Tools"): the records, the report, and reproduce.sh,
// which reruns the same cross-check on the same records with every option that decides the outcome and writes
// reproduced.json beside report.json. `hpsf crosscheck` and `hpsf fuzz` write it.
#ifndef HPSF_TOOLS_HPSF_REPRO_BUNDLE_H
#define HPSF_TOOLS_HPSF_REPRO_BUNDLE_H

#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/record.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "tools/checks/crosscheck.h"

namespace hpsf {

// `crosscheck_arguments` follow `hpsf crosscheck records.hpsfv`; they must not name --repro-dir or --json.
void WriteReproBundle(const std::string& dir, const RecordBatch& batch, const CrosscheckReport& report,
                      const std::vector<std::string>& crosscheck_arguments);

// The `hpsf crosscheck` options that give exactly this configuration, emulator, defect and Vulkan backend.
std::vector<std::string> CrosscheckArguments(const std::vector<std::string>& backends, const FilterConfig& config,
                                             const EmulatorOptions& emulator, Defect defect,
                                             const VulkanBackendOptions& vulkan);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_REPRO_BUNDLE_H
