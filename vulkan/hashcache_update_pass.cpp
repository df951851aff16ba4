#include "vulkan/hashcache_update_pass.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <utility>
#include <vector>

#include "hashcache_update_spv.h"
#include "vulkan/vulkan_internal.h"

namespace hpsf {
namespace {

constexpr std::size_t kElementBytes = 64;  // hashcache_update.comp's Element

struct Push {
  shared::CuckooParams params;
  std::int32_t cell_exponent, origin_x, origin_y, origin_z, resolution_log2;
  std::uint32_t stage;
  std::int32_t level, cells_log2;
  std::uint32_t positions, sample_count, sort_block, sort_stride, fixed64;
  float scale;
  std::uint32_t defect;
};
static_assert(sizeof(Push) <= 128, "push constants");

enum Stage : std::uint32_t { kSamples = 0, kLocate = 1, kSortStep = 2, kReduce = 3 };

// A level's data arrays on the device; an array the accumulation does not use is a 16-byte placeholder.
struct LevelBuffers {
  vulkan_internal::DeviceBuffer map, fronts, fixed_sums, float_sums, counts;
};

template <typename T>
std::size_t Bytes(const std::vector<T>& v) {
  return std::max<std::size_t>(v.size() * sizeof(T), 16);
}

}  // namespace

DeviceHashCacheUpdate UpdateHashCacheOnDevice(VulkanDevice& device, HashCache& cache,
                                              std::span<const HashCacheSample> samples, bool plain_store_claim) {
  using vulkan_internal::BindingKind;
  VulkanDevice::Impl& d = device.impl();
  const std::vector<BindingKind> kinds(11, BindingKind::kStorageBuffer);
  vulkan_internal::ComputeProgram program =
      vulkan_internal::CreateComputeProgram(d, hashcache_update_spv, kinds, sizeof(Push));
  const std::uint32_t positions = std::bit_ceil(std::max<std::uint32_t>(2, std::uint32_t(samples.size())));
  const std::size_t sample_bytes = std::max<std::size_t>(samples.size_bytes(), 16);
  vulkan_internal::DeviceBuffer sample_buffer = vulkan_internal::CreateDeviceBuffer(d, sample_bytes);
  vulkan_internal::DeviceBuffer elements[2] = {vulkan_internal::CreateDeviceBuffer(d, positions * kElementBytes),
                                               vulkan_internal::CreateDeviceBuffer(d, positions * kElementBytes)};
  vulkan_internal::DeviceBuffer orders = vulkan_internal::CreateDeviceBuffer(d, positions * sizeof(std::uint64_t));
  vulkan_internal::DeviceBuffer perm = vulkan_internal::CreateDeviceBuffer(d, positions * sizeof(std::uint32_t));
  vulkan_internal::DeviceBuffer counters = vulkan_internal::CreateDeviceBuffer(d, 2 * sizeof(std::uint32_t));
  std::vector<LevelBuffers> levels;
  std::vector<vulkan_internal::StagingBuffer> staging;
  {
    vulkan_internal::Transfer upload(d, staging);
    if (!samples.empty())
      std::memcpy(upload.Upload(sample_buffer, samples.size_bytes()), samples.data(), samples.size_bytes());
    std::memset(upload.Upload(counters, 2 * sizeof(std::uint32_t)), 0, 2 * sizeof(std::uint32_t));
    const auto put = [&](vulkan_internal::DeviceBuffer& buffer, const auto& words) {
      buffer = vulkan_internal::CreateDeviceBuffer(d, Bytes(words));
      if (!words.empty())
        std::memcpy(upload.Upload(buffer, words.size() * sizeof(words[0])), words.data(),
                    words.size() * sizeof(words[0]));
    };
    for (const HashCacheLevel& level : cache.levels) {
      LevelBuffers& b = levels.emplace_back();
      put(b.map, level.map.slots);
      put(b.fronts, level.data.front);
      put(b.fixed_sums, level.data.fixed_sums);
      put(b.float_sums, level.data.float_sums);
      put(b.counts, level.data.counts);
    }
    upload.Submit();
  }
  Push push{};
  push.cell_exponent = cache.grid.cell_exponent;
  push.origin_x = cache.grid.origin_x;
  push.origin_y = cache.grid.origin_y;
  push.origin_z = cache.grid.origin_z;
  push.resolution_log2 = cache.grid.resolution_log2;
  push.positions = positions;
  push.sample_count = std::uint32_t(samples.size());
  push.fixed64 = cache.accumulation == Accumulation::kFixed64 ? 1u : 0u;
  push.scale = SumScale(cache.accumulation, cache.fixed_point_bits);
  push.defect = plain_store_claim ? 1u : 0u;
  for (std::size_t l = 0; l < cache.levels.size(); ++l) {
    LevelBuffers& b = levels[l];
    vulkan_internal::DeviceBuffer* const buffers[] = {
        &sample_buffer,         &b.map,  &b.fronts, &b.fixed_sums, &b.float_sums, &b.counts, &elements[l % 2],
        &elements[(l + 1) % 2], &orders, &perm,     &counters};
    vulkan_internal::BindBuffers(d, program, buffers);
    push.params = cache.levels[l].map.params;
    push.level = cache.levels[l].level;
    push.cells_log2 = cache.levels[l].cells_log2;
    vulkan_internal::SubmitAndWait(d, [&](vk::raii::CommandBuffer& cb) {
      cb.bindPipeline(vk::PipelineBindPoint::eCompute, *program.pipeline);
      cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *program.layout, 0, *program.set, nullptr);
      const vk::MemoryBarrier barrier(vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eShaderRead,
                                      vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eShaderRead);
      const auto dispatch = [&](std::uint32_t stage, std::uint32_t items) {
        push.stage = stage;
        cb.pushConstants<Push>(*program.layout, vk::ShaderStageFlagBits::eCompute, 0, push);
        cb.dispatch(vulkan_internal::WorkgroupsFor(items, 64), 1, 1);
        cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {},
                           barrier, nullptr, nullptr);
      };
      if (l == 0) dispatch(kSamples, positions);
      dispatch(kLocate, positions);
      for (push.sort_block = 2; push.sort_block <= positions; push.sort_block *= 2) {
        for (push.sort_stride = push.sort_block / 2; push.sort_stride > 0; push.sort_stride /= 2) {
          dispatch(kSortStep, positions / 2);
        }
      }
      dispatch(kReduce, positions);
    });
  }
  DeviceHashCacheUpdate result;
  {
    vulkan_internal::Transfer download(d, staging);
    const void* read_counters = download.Download(counters, 2 * sizeof(std::uint32_t));
    std::vector<std::array<const void*, 4>> level_reads;
    for (std::size_t l = 0; l < cache.levels.size(); ++l) {
      const HashCacheData& data = cache.levels[l].data;
      level_reads.push_back({download.Download(levels[l].fronts, data.front.size() * sizeof(std::uint32_t)),
                             download.Download(levels[l].fixed_sums, Bytes(data.fixed_sums)),
                             download.Download(levels[l].float_sums, Bytes(data.float_sums)),
                             download.Download(levels[l].counts, data.counts.size() * sizeof(std::uint64_t))});
    }
    download.Submit();
    std::uint32_t words[2];
    std::memcpy(words, read_counters, sizeof words);
    result.missed = words[0];
    result.lost = words[1];
    for (std::size_t l = 0; l < cache.levels.size(); ++l) {
      HashCacheData& data = cache.levels[l].data;
      std::memcpy(data.front.data(), level_reads[l][0], data.front.size() * sizeof(std::uint32_t));
      if (!data.fixed_sums.empty()) {
        std::memcpy(data.fixed_sums.data(), level_reads[l][1], data.fixed_sums.size() * sizeof(std::uint64_t));
      }
      if (!data.float_sums.empty()) {
        std::memcpy(data.float_sums.data(), level_reads[l][2], data.float_sums.size() * sizeof(float));
      }
      std::memcpy(data.counts.data(), level_reads[l][3], data.counts.size() * sizeof(std::uint64_t));
    }
  }
  return result;
}

}  // namespace hpsf
