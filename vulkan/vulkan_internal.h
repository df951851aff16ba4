// Vulkan-Hpp RAII objects behind VulkanDevice, and the few building blocks every pass uses: device buffers and
// the transfers that fill and read them, a compute program (shader, bindings, push constants) and a one-shot
// submission timed with timestamp queries. Included only by vulkan/*.cpp.
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
  std::uint32_t kernel_memory_type = 0;  // see StagingPolicy
  std::uint32_t staging_memory_type = 0;
  VulkanDeviceInfo info;
};

namespace vulkan_internal {

// A buffer the kernels use, in DEVICE_LOCAL memory. On an unstaged device the host maps it (`mapped`); on a
// staged one `mapped` is null and data moves through a Transfer.
struct DeviceBuffer {
  vk::raii::Buffer buffer{nullptr};
  vk::raii::DeviceMemory memory{nullptr};
  vk::raii::BufferView texels{nullptr};  // an RGBA32UI view, for buffers read as texel buffers
  void* mapped = nullptr;
  vk::DeviceSize size = 0;
};

DeviceBuffer CreateDeviceBuffer(VulkanDevice::Impl& device, vk::DeviceSize size);

// The host's side of a copy: HOST_VISIBLE and HOST_COHERENT memory, HOST_CACHED where the device has it (reads
// of uncached memory crawl), mapped for its lifetime.
struct StagingBuffer {
  vk::raii::Buffer buffer{nullptr};
  vk::raii::DeviceMemory memory{nullptr};
  void* mapped = nullptr;
  vk::DeviceSize size = 0;
};

// Moves data between the host and DeviceBuffers on either kind of device. The host writes where Upload points
// and reads where Download points; Submit runs the staging copies (none on an unstaged device) in one timed
// submission. Staging buffers come from `pool`, kept by the caller from run to run and grown when too small.
class Transfer {
 public:
  Transfer(VulkanDevice::Impl& device, std::vector<StagingBuffer>& pool) : device_(device), pool_(pool) {}
  // Where the host writes the first `bytes` of `buffer`, to be copied in by Submit.
  void* Upload(DeviceBuffer& buffer, vk::DeviceSize bytes);
  // Where the host reads the first `bytes` of `buffer` once Submit has returned.
  const void* Download(DeviceBuffer& buffer, vk::DeviceSize bytes);
  // The copies, timed on the device; 0 ms without any.
  double Submit();
  vk::DeviceSize bytes() const { return bytes_; }

 private:
  struct Copy {
    vk::Buffer from, to;
    vk::DeviceSize bytes;
  };
  StagingBuffer& Staging(vk::DeviceSize bytes);
  VulkanDevice::Impl& device_;
  std::vector<StagingBuffer>& pool_;
  std::size_t used_ = 0;
  std::vector<Copy> copies_;
  vk::DeviceSize bytes_ = 0;
};

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
void BindBuffers(VulkanDevice::Impl& device, ComputeProgram& program, std::span<DeviceBuffer* const> buffers);

// Workgroups for `items` at `per_workgroup` each, at least 1 and at most 65535 (the guaranteed minimum of
// maxComputeWorkGroupCount[0]); the shaders loop, so a clamped dispatch still covers every item.
std::uint32_t WorkgroupsFor(std::uint32_t items, std::uint32_t per_workgroup);

// Records work into a fresh command buffer between two timestamps, submits it, waits, and returns the device
// time between the timestamps in milliseconds. The work sees every earlier submission's writes, and the host
// sees its writes once this returns.
double SubmitAndWait(VulkanDevice::Impl& device, const std::function<void(vk::raii::CommandBuffer&)>& record);

}  // namespace vulkan_internal
}  // namespace hpsf

#endif  // HPSF_VULKAN_VULKAN_INTERNAL_H
