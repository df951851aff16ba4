// Vulkan-Hpp RAII objects behind VulkanDevice, and the few building blocks every pass uses: host-visible
// storage buffers, a compute program (shader, bindings, push constants) and a one-shot submission timed with
// timestamp queries. Included only by vulkan/*.cpp.
#ifndef HPSF_VULKAN_VULKAN_INTERNAL_H
#define HPSF_VULKAN_VULKAN_INTERNAL_H

#include <cstdint>
#include <functional>
#include <span>

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
  void* mapped = nullptr;
  vk::DeviceSize size = 0;
};

HostBuffer CreateHostBuffer(VulkanDevice::Impl& device, vk::DeviceSize size);

// A compute pipeline whose bindings 0..binding_count-1 are storage buffers, with one push-constant block.
struct ComputeProgram {
  vk::raii::ShaderModule module{nullptr};
  vk::raii::DescriptorSetLayout set_layout{nullptr};
  vk::raii::PipelineLayout layout{nullptr};
  vk::raii::Pipeline pipeline{nullptr};
  vk::raii::DescriptorPool pool{nullptr};
  vk::raii::DescriptorSet set{nullptr};
  std::uint32_t push_constant_size = 0;
};

ComputeProgram CreateComputeProgram(VulkanDevice::Impl& device, std::span<const std::uint32_t> spirv,
                                    std::uint32_t binding_count, std::uint32_t push_constant_size);

// Points binding i of the program at buffers[i].
void BindBuffers(VulkanDevice::Impl& device, ComputeProgram& program, std::span<HostBuffer* const> buffers);

// Records work into a fresh command buffer between two timestamps, submits it, waits, and returns the device
// time between the timestamps in milliseconds.
double SubmitAndWait(VulkanDevice::Impl& device, const std::function<void(vk::raii::CommandBuffer&)>& record);

}  // namespace vulkan_internal
}  // namespace hpsf

#endif  // HPSF_VULKAN_VULKAN_INTERNAL_H
