// keys.comp on a Vulkan device: the key path of core/shared/key.h for a batch of records, read back for the
// level-1 cross-check. Upload once, dispatch as often as wanted (benchmarks time steady-state dispatches).
#ifndef HPSF_VULKAN_KEY_PASS_H
#define HPSF_VULKAN_KEY_PASS_H

#include <memory>
#include <span>
#include <vector>

#include "core/key_batch.h"
#include "core/record.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

class KeyPass {
 public:
  explicit KeyPass(VulkanDevice& device);
  ~KeyPass();
  KeyPass(const KeyPass&) = delete;
  KeyPass& operator=(const KeyPass&) = delete;

  void Upload(std::span<const Record> records);
  // Runs keys.comp over the uploaded records and waits; returns the device time from timestamps, in ms.
  double Dispatch(const KeyParams& params);
  std::vector<KeyResult> Download();

  // Upload, Dispatch, Download.
  std::vector<KeyResult> Run(std::span<const Record> records, const KeyParams& params);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hpsf

#endif  // HPSF_VULKAN_KEY_PASS_H
