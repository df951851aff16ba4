// hashcache_update.comp on a Vulkan device: a frame's sort-and-reduce update of the HashCache (core/hashcache_update.h
// holds the reference's), one submission a level, the next level's element count read back in between (its
// elements are the segments this level appended), every level's data read back into the cache at the end.
#ifndef HPSF_VULKAN_HASHCACHE_UPDATE_PASS_H
#define HPSF_VULKAN_HASHCACHE_UPDATE_PASS_H

#include <cstdint>
#include <memory>
#include <span>

#include "core/hashcache.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

struct DeviceHashCacheUpdate {
  std::uint32_t missed = 0;  // samples off the grid or in a cell no triangle occupies
  std::uint32_t lost = 0;    // elements above the finest level whose cell is not in the map
};

// The pipeline, made once for the frames of a run. The device must outlive the pass.
class HashCacheUpdatePass {
 public:
  explicit HashCacheUpdatePass(VulkanDevice& device);
  ~HashCacheUpdatePass();
  HashCacheUpdatePass(const HashCacheUpdatePass&) = delete;
  HashCacheUpdatePass& operator=(const HashCacheUpdatePass&) = delete;

  // `plain_store_claim`: the broken variant, the front claimed by a load and a store.
  DeviceHashCacheUpdate Run(HashCache& cache, std::span<const HashCacheSample> samples, bool plain_store_claim = false);

 private:
  struct State;
  VulkanDevice& device_;
  std::unique_ptr<State> state_;
};

}  // namespace hpsf

#endif  // HPSF_VULKAN_HASHCACHE_UPDATE_PASS_H
