// The repro bundle a failed check leaves behind (docs/design/README.md): the records, the report, copies of the user's
// shaders (shaders/accumulate.spv, shaders/eviction.spv), and reproduce.sh, which reruns the same cross-check on
// the same records with every option that decides the outcome and writes reproduced.json beside report.json. Every
// path in it is relative to the bundle, and reproduce.sh finds hpsf through $HPSF or PATH and warns when its
// version is not the one that wrote the bundle: a CI job uploads the folder, and it reproduces anywhere.
// `hpsf crosscheck` and `hpsf fuzz` write it.
#ifndef HPSF_TOOLS_HPSF_REPRO_BUNDLE_H
#define HPSF_TOOLS_HPSF_REPRO_BUNDLE_H

#include <span>
#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/record.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf {

// `crosscheck_arguments` follow `hpsf crosscheck records.hpsfv`; they must not name --repro-dir, --json or
// --frame (records.hpsfv holds the frames with their numbers).
void WriteReproBundle(const std::string& dir, std::span<const RecordBatch> frames, const CrosscheckReport& report,
                      const std::vector<std::string>& crosscheck_arguments);

// The `hpsf crosscheck` options that give exactly this configuration, emulator, defect and Vulkan backend.
std::vector<std::string> CrosscheckArguments(const std::vector<std::string>& backends, const FilterConfig& config,
                                             const EmulatorOptions& emulator, Defect defect,
                                             const VulkanBackendOptions& vulkan);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_REPRO_BUNDLE_H
