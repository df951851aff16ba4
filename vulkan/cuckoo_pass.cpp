#include "vulkan/cuckoo_pass.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "cuckoo_spv.h"
#include "vulkan/vulkan_internal.h"

namespace hpsf {

CuckooBuild BuildCuckooMapOnDevice(VulkanDevice& device, std::span<const std::uint32_t> keys,
                                   const CuckooBuildOptions& options) {
  struct Push {
    shared::CuckooParams params;
    std::uint32_t key_count, max_chain;
  };
  using vulkan_internal::BindingKind;
  constexpr BindingKind kBindings[] = {BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
                                       BindingKind::kStorageBuffer};
  VulkanDevice::Impl& d = device.impl();
  vulkan_internal::ComputeProgram program =
      vulkan_internal::CreateComputeProgram(d, cuckoo_spv, kBindings, sizeof(Push));
  const std::size_t key_bytes = std::max<std::size_t>(keys.size_bytes(), 16);
  vulkan_internal::DeviceBuffer key_buffer = vulkan_internal::CreateDeviceBuffer(d, key_bytes);
  vulkan_internal::DeviceBuffer failed = vulkan_internal::CreateDeviceBuffer(d, sizeof(std::uint32_t));
  std::vector<vulkan_internal::StagingBuffer> staging;
  {
    vulkan_internal::Transfer upload(d, staging);
    if (!keys.empty()) std::memcpy(upload.Upload(key_buffer, keys.size_bytes()), keys.data(), keys.size_bytes());
    upload.Submit();
  }
  CuckooBuild build;
  double space = options.space;
  for (build.attempts = 1; build.attempts <= options.max_attempts; ++build.attempts, space *= options.growth) {
    const std::uint32_t size = CuckooSlots(keys.size(), space);
    const Push push{shared::CuckooFunctions(options.seed, options.level, build.attempts, size, options.functions),
                    static_cast<std::uint32_t>(keys.size()), CuckooMaxChain(keys.size(), options)};
    vulkan_internal::DeviceBuffer slots = vulkan_internal::CreateDeviceBuffer(d, size * sizeof(std::uint32_t));
    {
      vulkan_internal::Transfer upload(d, staging);
      std::memset(upload.Upload(slots, size * sizeof(std::uint32_t)), 0xFF, size * sizeof(std::uint32_t));
      std::memset(upload.Upload(failed, sizeof(std::uint32_t)), 0, sizeof(std::uint32_t));
      upload.Submit();
    }
    vulkan_internal::DeviceBuffer* const buffers[] = {&key_buffer, &slots, &failed};
    vulkan_internal::BindBuffers(d, program, buffers);
    const auto groups = std::clamp<std::uint32_t>(std::uint32_t((keys.size() + 63) / 64), 1, 65535);
    vulkan_internal::SubmitAndWait(d, [&](vk::raii::CommandBuffer& cb) {
      cb.bindPipeline(vk::PipelineBindPoint::eCompute, *program.pipeline);
      cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *program.layout, 0, *program.set, nullptr);
      cb.pushConstants<Push>(*program.layout, vk::ShaderStageFlagBits::eCompute, 0, push);
      cb.dispatch(groups, 1, 1);
    });
    build.map.params = push.params;
    build.map.slots.resize(size);
    std::uint32_t failures = 0;
    vulkan_internal::Transfer download(d, staging);
    const void* read_slots = download.Download(slots, size * sizeof(std::uint32_t));
    const void* read_failed = download.Download(failed, sizeof(std::uint32_t));
    download.Submit();
    std::memcpy(build.map.slots.data(), read_slots, size * sizeof(std::uint32_t));
    std::memcpy(&failures, read_failed, sizeof failures);
    if (failures == 0) {
      build.built = true;
      return build;
    }
  }
  build.attempts = options.max_attempts;
  return build;
}

}  // namespace hpsf
