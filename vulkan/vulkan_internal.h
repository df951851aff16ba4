// Vulkan-Hpp RAII objects behind VulkanDevice, and the few building blocks every pass uses: host-visible
// storage buffers, a compute program (shader, bindings, push constants) and a one-shot submission timed with
// timestamp queries. Included only by vulkan/*.cpp.
#ifndef HPSF_VULKAN_VULKAN_INTERNAL_H
#define HPSF_VULKAN_VULKAN_INTERNAL_H

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

#include "vulkan/vulkan_device.h"

namespace hpsf {

struct VulkanDevice::Impl {
  vk::raii::Context context;
  vk::raii::Instance instance{nullptr};
  vk::raii::PhysicalDevice physical{nullptr};
  vk::raii::Device device{nullptr};
  vk::raii::Queue queue{nullptr};
  std::uint32_t queue_family = 0;
  vk::raii::CommandPool command_pool{nullptr};
  vk::raii::QueryPool timestamps{nullptr};  // two queries: before and after the recorded work
  double timestamp_period_ns = 1.0;
  VulkanDeviceInfo info;
};

namespace vulkan_internal {

// A storage buffer in host-visible, host-coherent memory, mapped for its lifetime. lavapipe has only such memory;
// on a discrete GPU it is correct but not the fastest choice.
struct HostBuffer {
  vk::raii::Buffer buffer{nullptr};
  vk::raii::DeviceMemory memory{nullptr};
  vk::raii::BufferView texels{nullptr};  // an RGBA32UI view, for buffers read as texel buffers
  void* mapped = nullptr;
  vk::DeviceSize size = 0;
};

HostBuffer CreateHostBuffer(VulkanDevice::Impl& device, vk::DeviceSize size);

// How a shader sees a buffer. Record batches are read through uniform texel buffers of RGBA32UI: lavapipe
// fetches a whole texel per lane with vector gathers, where a storage-buffer load costs a scalar loop per
// lane and per load, and texel buffers reach 2^27 texels where lavapipe's storage range stops at 128 MiB.
enum class BindingKind { kStorageBuffer, kUniformTexelBuffer };

// A compute pipeline with one binding per entry of `bindings`, in order, and one push-constant block.
struct ComputeProgram {
  vk::raii::ShaderModule module{nullptr};
  vk::raii::DescriptorSetLayout set_layout{nullptr};
  vk::raii::PipelineLayout layout{nullptr};
  vk::raii::Pipeline pipeline{nullptr};
  vk::raii::DescriptorPool pool{nullptr};
  vk::raii::DescriptorSet set{nullptr};
  std::vector<BindingKind> bindings;
  std::uint32_t push_constant_size = 0;
};

ComputeProgram CreateComputeProgram(VulkanDevice::Impl& device, std::span<const std::uint32_t> spirv,
                                    std::span<const BindingKind> bindings, std::uint32_t push_constant_size);

// Points binding i of the program at buffers[i]; a texel binding gets the buffer's RGBA32UI view.
void BindBuffers(VulkanDevice::Impl& device, ComputeProgram& program, std::span<HostBuffer* const> buffers);

// Workgroups for `items` at `per_workgroup` each, at least 1 and at most 65535 (the guaranteed minimum of
// maxComputeWorkGroupCount[0]); the shaders loop, so a clamped dispatch still covers every item.
std::uint32_t WorkgroupsFor(std::uint32_t items, std::uint32_t per_workgroup);

// Records work into a fresh command buffer between two timestamps, submits it, waits, and returns the device
// time between the timestamps in milliseconds.
double SubmitAndWait(VulkanDevice::Impl& device, const std::function<void(vk::raii::CommandBuffer&)>& record);

}  // namespace vulkan_internal
}  // namespace hpsf

#endif  // HPSF_VULKAN_VULKAN_INTERNAL_H
