// Which backend filters a batch and what it reports (the options come from emulator_options.h): shared by render,
// replay and crosscheck.
#ifndef HPSF_TOOLS_HPSF_BACKEND_OPTIONS_H
#define HPSF_TOOLS_HPSF_BACKEND_OPTIONS_H

#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/backend.h"
#include "core/filter_config.h"
#include "core/image.h"
#include "core/record.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "reference/reference_filter.h"
#include "tools/hpsf/emulator_options.h"
#include "verifier/contract/backend_factory.h"
#include "verifier/contract/crosscheck.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf {

// A backend by name (core/backend_registry.h: a ConfigError naming --backend otherwise), made with its options.
BackendInstance MakeBackend(const std::string& backend, const EmulatorOptions& emulator, Defect defect = Defect::kNone,
                            const VulkanBackendOptions& vulkan = {});

// The last frame's image, from whichever backend filtered it.
const Image& LastFrameImage(const Backend& backend);
// The last frame's eviction, for a report's per-frame entry: cells_evicted (reference), or evicted, tombstones
// and eviction_s, the evict and reclaim passes' time (hashed backends).
nlohmann::json LastFrameEviction(const Backend& backend);
// The temporal blend's pass time of the last frame: {"temporal_s": seconds} for a hashed backend; the reference
// blends inside its filter ({}).
nlohmann::json LastFrameTemporal(const Backend& backend);
// The occupied list of the last frame (--compaction occupied-list): its length after the frame and the gather's
// time, for a hashed backend; the reference's map holds its cells alone ({}).
nlohmann::json LastFrameCompaction(const Backend& backend);
// The last frame's level seeds (--level-change seed): cells_seeded (reference), or seeded and level_seed_s, the
// seed pass's time (hashed backends).
nlohmann::json LastFrameLevelSeed(const Backend& backend);
// packed-decimal's settle of the last frame: cells_halved (reference), or halved and settle_s, the pass's time
// (hashed backends).
nlohmann::json LastFrameSettle(const Backend& backend);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_BACKEND_OPTIONS_H
