#include "vulkan/occupancy_pass.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "occupancy_spv.h"
#include "vulkan/vulkan_internal.h"

namespace hpsf {

DeviceOccupancy VoxelizeOnDevice(VulkanDevice& device, const shared::OccupancyGrid& grid,
                                 std::span<const OccupancyTriangle> triangles, int level) {
  struct Push {
    std::int32_t cell_exponent, origin_x, origin_y, origin_z, resolution_log2, level;
    std::uint32_t triangle_count, pass;
  };
  using vulkan_internal::BindingKind;
  constexpr BindingKind kBindings[] = {BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
                                       BindingKind::kStorageBuffer};
  VulkanDevice::Impl& d = device.impl();
  vulkan_internal::ComputeProgram program =
      vulkan_internal::CreateComputeProgram(d, occupancy_spv, kBindings, sizeof(Push));
  std::vector<glm::vec4> vertices;
  for (const OccupancyTriangle& t : triangles) {
    for (const glm::vec3& v : t) vertices.emplace_back(v, 0.0f);
  }
  const OccupancyLevel empty(grid, level);
  const std::size_t word_bytes = empty.words().size() * sizeof(std::uint32_t);
  const std::size_t vertex_bytes = std::max<std::size_t>(vertices.size() * sizeof(glm::vec4), 16);
  vulkan_internal::DeviceBuffer input = vulkan_internal::CreateDeviceBuffer(d, vertex_bytes);
  vulkan_internal::DeviceBuffer field = vulkan_internal::CreateDeviceBuffer(d, word_bytes);
  vulkan_internal::DeviceBuffer count = vulkan_internal::CreateDeviceBuffer(d, sizeof(std::uint64_t));
  std::vector<vulkan_internal::StagingBuffer> staging;
  vulkan_internal::Transfer upload(d, staging);
  if (!vertices.empty()) std::memcpy(upload.Upload(input, vertex_bytes), vertices.data(), vertex_bytes);
  std::memset(upload.Upload(field, word_bytes), 0, word_bytes);
  std::memset(upload.Upload(count, sizeof(std::uint64_t)), 0, sizeof(std::uint64_t));
  upload.Submit();
  vulkan_internal::DeviceBuffer* const buffers[] = {&input, &field, &count};
  vulkan_internal::BindBuffers(d, program, buffers);

  Push push{grid.cell_exponent,
            grid.origin_x,
            grid.origin_y,
            grid.origin_z,
            grid.resolution_log2,
            level,
            static_cast<std::uint32_t>(triangles.size()),
            0u};
  const auto groups = [](std::size_t n) { return std::clamp<std::uint32_t>(std::uint32_t((n + 63) / 64), 1, 65535); };
  vulkan_internal::SubmitAndWait(d, [&](vk::raii::CommandBuffer& cb) {
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *program.pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *program.layout, 0, *program.set, nullptr);
    cb.pushConstants<Push>(*program.layout, vk::ShaderStageFlagBits::eCompute, 0, push);
    cb.dispatch(groups(triangles.size()), 1, 1);
    // The count reads every word the marks wrote.
    const vk::MemoryBarrier barrier(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eShaderRead);
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {},
                       barrier, nullptr, nullptr);
    push.pass = 1u;
    cb.pushConstants<Push>(*program.layout, vk::ShaderStageFlagBits::eCompute, 0, push);
    cb.dispatch(groups(empty.words().size()), 1, 1);
  });
  std::vector<std::uint32_t> words(empty.words().size());
  std::uint64_t counted = 0;
  vulkan_internal::Transfer download(d, staging);
  const void* read_words = download.Download(field, word_bytes);
  const void* read_count = download.Download(count, sizeof(std::uint64_t));
  download.Submit();
  std::memcpy(words.data(), read_words, word_bytes);
  std::memcpy(&counted, read_count, sizeof counted);
  return {OccupancyLevel(grid, level, std::move(words)), counted};
}

}  // namespace hpsf
