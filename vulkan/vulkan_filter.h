// The Vulkan backend: the GPU hash table as GLSL compute shaders (vulkan/shaders/accumulate_*.comp, then
// resolve_*.comp) on a VulkanDevice, through the stable buffer interface of table_interface.glsl. Returns the
// image, the table, and per record its key and placement, read back for the table checker and the
// cross-check; device times from timestamp queries.
#ifndef HPSF_VULKAN_VULKAN_FILTER_H
#define HPSF_VULKAN_VULKAN_FILTER_H

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/hashed_run.h"
#include "core/record.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

// Kernel times from device timestamps; transfers split into the host's part and, on a staged device, the
// device's copies (timestamps), with the bytes moved each way.
struct VulkanTimings {
  double transport_ms = 0;       // device: several filtered bounces' lookups (transport_pass.h); 0 without
  double upload_ms = 0;          // host: records and input verdicts into mapped or staging memory
  double upload_copy_ms = 0;     // device: staging to device copies (0 when mapped)
  double accumulate_ms = 0;      // device: clearing the table and the accumulate dispatch (keys included)
  double resolve_ms = 0;         // device: the resolve dispatch
  double level_seed_ms = 0;      // device: the seed pass of --level-change seed
  double temporal_ms = 0;        // device: the temporal blend (the copy into the previous table is in accumulate)
  double compaction_ms = 0;      // device: the gather into the occupied list; 0 without --compaction
  double settle_ms = 0;          // device: packed-decimal's settle; 0 for other sums
  double eviction_ms = 0;        // device: the evict and reclaim dispatches (and the prune); 0 without eviction
  double read_back_copy_ms = 0;  // device: device to staging copies (0 when mapped)
  double read_back_ms = 0;       // host: image, table, keys and placements out of mapped or staging memory
  std::uint64_t upload_bytes = 0;
  std::uint64_t read_back_bytes = 0;
  double FilterMs() const {
    return transport_ms + accumulate_ms + level_seed_ms + compaction_ms + settle_ms + temporal_ms + eviction_ms +
           resolve_ms;
  }
  double UploadMs() const { return upload_ms + upload_copy_ms; }
  double ReadBackMs() const { return read_back_copy_ms + read_back_ms; }
};

struct VulkanRun : HashedRun {
  VulkanTimings timings;
  std::string accumulate_shader;  // "built-in" or the file given with --accumulate-spv
};

class VulkanFilter {
 public:
  // accumulate_spv: the path of a user's accumulate shader (SPIR-V) to run in place of the built-in one,
  // through the same bindings; empty for the built-in shaders. InputError naming the file when it is not SPIR-V.
  // eviction_spv: likewise for the eviction pass (eviction.comp's bindings and push constants), temporal_spv for
  // the temporal blend (temporal.comp's), resolve_spv for the resolve (resolve.glsl's; its sums binding says its mode),
  // compaction_spv for the occupied list's passes of --compaction occupied-list (compaction.comp's), transport_spv
  // for several filtered bounces' transport (transport.comp's).
  explicit VulkanFilter(VulkanDevice& device, const std::string& accumulate_spv = "",
                        const std::string& eviction_spv = "", const std::string& temporal_spv = "",
                        const std::string& resolve_spv = "", const std::string& compaction_spv = "",
                        const std::string& transport_spv = "");
  ~VulkanFilter();
  VulkanFilter(const VulkanFilter&) = delete;
  VulkanFilter& operator=(const VulkanFilter&) = delete;

  // Throws ConfigError when the table or the batch exceeds what the device can bind.
  // keep_table: the frame adds to the device table the previous Run left, and keeps its F (a sequence of frames,
  // core/backend.h); a ConfigError when there is none of this shape. Else the table starts empty and F is chosen
  // for this batch (and config.frames).
  // effects: the passes the frame runs (core/effect_plan.h); null plans them for the first frame or, with
  // keep_table, for a later one.
  VulkanRun Run(const RecordBatch& batch, const FilterConfig& config, bool keep_table = false,
                const FrameEffects* effects = nullptr);

  // Makes `table` the device table a Run with keep_table carries on from, as if a frame had left it: its tags,
  // sums, counts and last-seen frames (zero when it has none), and its F. For tables no frame reaches in a test's
  // time (a count near 2^64, docs/design/defects.md, D12) and for starting from a dump.
  void LoadTable(const HashTableDump& table);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hpsf

#endif  // HPSF_VULKAN_VULKAN_FILTER_H
