#include "vulkan/fixed_point_pass.h"

#include <algorithm>
#include <cstring>

#include "core/shared/float_bits.h"
#include "fixed_point_spv.h"
#include "vulkan/vulkan_internal.h"

namespace hpsf {

std::vector<std::uint64_t> ToFixedPointOnDevice(VulkanDevice& device, std::span<const float> values,
                                                int fraction_bits) {
  struct Push {
    float scale;
    std::uint32_t count;
  };
  using vulkan_internal::BindingKind;
  constexpr BindingKind kBindings[] = {BindingKind::kStorageBuffer, BindingKind::kStorageBuffer};
  VulkanDevice::Impl& d = device.impl();
  vulkan_internal::ComputeProgram program =
      vulkan_internal::CreateComputeProgram(d, fixed_point_spv, kBindings, sizeof(Push));
  vulkan_internal::DeviceBuffer input = vulkan_internal::CreateDeviceBuffer(d, values.size_bytes());
  vulkan_internal::DeviceBuffer output = vulkan_internal::CreateDeviceBuffer(d, values.size() * sizeof(std::uint64_t));
  std::vector<vulkan_internal::StagingBuffer> staging;
  vulkan_internal::Transfer upload(d, staging);
  if (!values.empty()) std::memcpy(upload.Upload(input, values.size_bytes()), values.data(), values.size_bytes());
  upload.Submit();
  vulkan_internal::DeviceBuffer* const buffers[] = {&input, &output};
  vulkan_internal::BindBuffers(d, program, buffers);

  const Push push{shared::PowerOfTwo(fraction_bits), static_cast<std::uint32_t>(values.size())};
  const std::uint32_t groups = std::clamp<std::uint32_t>((push.count + 127) / 128, 1, 65535);
  vulkan_internal::SubmitAndWait(d, [&](vk::raii::CommandBuffer& cb) {
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *program.pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *program.layout, 0, *program.set, nullptr);
    cb.pushConstants<Push>(*program.layout, vk::ShaderStageFlagBits::eCompute, 0, push);
    cb.dispatch(groups, 1, 1);
  });
  std::vector<std::uint64_t> fixed(values.size());
  vulkan_internal::Transfer download(d, staging);
  const void* read = download.Download(output, fixed.size() * sizeof(std::uint64_t));
  download.Submit();
  if (!fixed.empty()) std::memcpy(fixed.data(), read, fixed.size() * sizeof(std::uint64_t));
  return fixed;
}

}  // namespace hpsf
