#include "vulkan/hashcache_update_pass.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/error.h"
#include "hashcache_update_spv.h"
#include "vulkan/vulkan_internal.h"

namespace hpsf {
namespace {

constexpr std::size_t kElementBytes = 64;      // hashcache_update.comp's Element
constexpr std::uint32_t kLocalSortSpan = 512;  // and its kLocalSortSpan
constexpr std::uint32_t kWorkgroup = 256;

struct Push {
  shared::CuckooParams params;
  std::int32_t cell_exponent, origin_x, origin_y, origin_z, resolution_log2;
  std::uint32_t stage;
  std::int32_t level, cells_log2;
  std::uint32_t positions, element_count, sort_block, sort_stride, fixed64;
  float scale;
  std::uint32_t defect;
};
static_assert(sizeof(Push) <= 128, "push constants");

enum Stage : std::uint32_t {
  kSamples = 0,
  kLocate = 1,
  kSortStep = 2,
  kReduce = 3,
  kResetAppended = 4,
  kLocalSort = 5,
  kAtomicUpdate = 6
};

// A level's data arrays on the device; an array the accumulation does not use is a 16-byte placeholder.
struct LevelBuffers {
  vulkan_internal::DeviceBuffer map, fronts, fixed_sums, float_sums, counts;
};

template <typename T>
std::size_t Bytes(const std::vector<T>& v) {
  return std::max<std::size_t>(v.size() * sizeof(T), 16);
}

// The sort's span for `elements`: a power of two, at least a workgroup's block.
std::uint32_t SpanFor(std::uint32_t elements) { return std::max(kLocalSortSpan, std::bit_ceil(elements)); }

}  // namespace

struct HashCacheUpdatePass::State {
  vulkan_internal::ComputeProgram program;
};

HashCacheUpdatePass::HashCacheUpdatePass(VulkanDevice& device) : device_(device) {
  const std::vector<vulkan_internal::BindingKind> kinds(11, vulkan_internal::BindingKind::kStorageBuffer);
  state_ = std::make_unique<State>(
      State{vulkan_internal::CreateComputeProgram(device_.impl(), hashcache_update_spv, kinds, sizeof(Push))});
}

HashCacheUpdatePass::~HashCacheUpdatePass() = default;

DeviceHashCacheUpdate HashCacheUpdatePass::Run(HashCache& cache, std::span<const HashCacheSample> samples,
                                               bool plain_store_claim) {
  VulkanDevice::Impl& d = device_.impl();
  vulkan_internal::ComputeProgram& program = state_->program;
  if (samples.size() > (std::size_t(65535) * kLocalSortSpan)) {
    throw std::logic_error("a HashCache update of more samples than a dispatch's workgroups can sort");
  }
  const bool atomics = cache.update == HashCacheUpdateRule::kAtomics;
  // The atomics rule reads the samples alone: its elements, orders and permutation are placeholders.
  const std::size_t span = atomics ? 1 : SpanFor(std::uint32_t(samples.size()));
  const vk::DeviceSize storage_range = d.physical.getProperties().limits.maxStorageBufferRange;
  if (std::max<vk::DeviceSize>(span * kElementBytes, samples.size_bytes()) > storage_range) {
    throw InputError("the HashCache's update of " + std::to_string(samples.size()) + " samples needs " +
                     std::to_string(std::max<vk::DeviceSize>(span * kElementBytes, samples.size_bytes())) +
                     " bytes in one buffer, more than the " + std::to_string(storage_range) + " bytes '" +
                     device_.info().name + "' can bind: fewer samples a frame (--size, --spp)");
  }
  vulkan_internal::DeviceBuffer sample_buffer =
      vulkan_internal::CreateDeviceBuffer(d, std::max<std::size_t>(samples.size_bytes(), 16));
  vulkan_internal::DeviceBuffer elements[2] = {vulkan_internal::CreateDeviceBuffer(d, span * kElementBytes),
                                               vulkan_internal::CreateDeviceBuffer(d, span * kElementBytes)};
  vulkan_internal::DeviceBuffer orders = vulkan_internal::CreateDeviceBuffer(d, span * sizeof(std::uint64_t));
  vulkan_internal::DeviceBuffer perm = vulkan_internal::CreateDeviceBuffer(d, span * sizeof(std::uint32_t));
  vulkan_internal::DeviceBuffer counters = vulkan_internal::CreateDeviceBuffer(d, 4 * sizeof(std::uint32_t));
  std::vector<LevelBuffers> levels;
  std::vector<vulkan_internal::StagingBuffer> staging;
  {
    vulkan_internal::Transfer upload(d, staging);
    if (!samples.empty()) {
      std::memcpy(upload.Upload(sample_buffer, samples.size_bytes()), samples.data(), samples.size_bytes());
    }
    std::memset(upload.Upload(counters, 4 * sizeof(std::uint32_t)), 0, 4 * sizeof(std::uint32_t));
    const auto put = [&](vulkan_internal::DeviceBuffer& buffer, const auto& words) {
      buffer = vulkan_internal::CreateDeviceBuffer(d, Bytes(words));
      if (!words.empty()) {
        std::memcpy(upload.Upload(buffer, words.size() * sizeof(words[0])), words.data(),
                    words.size() * sizeof(words[0]));
      }
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
  push.fixed64 = cache.accumulation == Accumulation::kFixed64 ? 1u : 0u;
  push.scale = SumScale(cache.accumulation, cache.fixed_point_bits);
  push.defect = plain_store_claim ? 1u : 0u;
  std::uint32_t element_count = std::uint32_t(samples.size());
  std::array<std::uint32_t, 3> counted{};  // missed, lost, appended
  for (std::size_t l = 0; l < cache.levels.size() && (atomics || l == 0 || element_count > 0); ++l) {
    LevelBuffers& b = levels[l];
    vulkan_internal::DeviceBuffer* const buffers[] = {
        &sample_buffer,         &b.map,  &b.fronts, &b.fixed_sums, &b.float_sums, &b.counts, &elements[l % 2],
        &elements[(l + 1) % 2], &orders, &perm,     &counters};
    vulkan_internal::BindBuffers(d, program, buffers);
    push.params = cache.levels[l].map.params;
    push.level = cache.levels[l].level;
    push.cells_log2 = cache.levels[l].cells_log2;
    push.element_count = element_count;
    push.positions = SpanFor(element_count);
    vulkan_internal::SubmitAndWait(d, [&](vk::raii::CommandBuffer& cb) {
      cb.bindPipeline(vk::PipelineBindPoint::eCompute, *program.pipeline);
      cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *program.layout, 0, *program.set, nullptr);
      const vk::MemoryBarrier barrier(vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eShaderRead,
                                      vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eShaderRead);
      const auto dispatch = [&](std::uint32_t stage, std::uint32_t groups) {
        push.stage = stage;
        cb.pushConstants<Push>(*program.layout, vk::ShaderStageFlagBits::eCompute, 0, push);
        cb.dispatch(groups, 1, 1);
        cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {},
                           barrier, nullptr, nullptr);
      };
      const std::uint32_t per_position = vulkan_internal::WorkgroupsFor(push.positions, kWorkgroup);
      if (atomics) {
        push.element_count = std::uint32_t(samples.size());
        dispatch(kAtomicUpdate, vulkan_internal::WorkgroupsFor(push.element_count, kWorkgroup));
        return;
      }
      dispatch(kResetAppended, 1);
      if (l == 0) dispatch(kSamples, per_position);
      dispatch(kLocate, per_position);
      // Block sizes up to the local span at once, then each larger one: its strides of the local span or more one
      // dispatch each, the rest in workgroup memory.
      const std::uint32_t blocks = push.positions / kLocalSortSpan;
      push.sort_block = 0;
      dispatch(kLocalSort, blocks);
      for (push.sort_block = 2 * kLocalSortSpan; push.sort_block <= push.positions; push.sort_block *= 2) {
        for (push.sort_stride = push.sort_block / 2; push.sort_stride >= kLocalSortSpan; push.sort_stride /= 2) {
          dispatch(kSortStep, vulkan_internal::WorkgroupsFor(push.positions / 2, kWorkgroup));
        }
        dispatch(kLocalSort, blocks);
      }
      dispatch(kReduce, per_position);
    });
    vulkan_internal::Transfer download(d, staging);
    const void* read = download.Download(counters, 3 * sizeof(std::uint32_t));
    download.Submit();
    std::memcpy(counted.data(), read, sizeof counted);
    element_count = atomics ? std::uint32_t(samples.size()) : counted[2];
  }
  DeviceHashCacheUpdate result;
  result.missed = counted[0];
  result.lost = counted[1];
  vulkan_internal::Transfer download(d, staging);
  std::vector<std::array<const void*, 4>> level_reads;
  for (std::size_t l = 0; l < cache.levels.size(); ++l) {
    const HashCacheData& data = cache.levels[l].data;
    level_reads.push_back({download.Download(levels[l].fronts, data.front.size() * sizeof(std::uint32_t)),
                           download.Download(levels[l].fixed_sums, Bytes(data.fixed_sums)),
                           download.Download(levels[l].float_sums, Bytes(data.float_sums)),
                           download.Download(levels[l].counts, data.counts.size() * sizeof(std::uint64_t))});
  }
  download.Submit();
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
  return result;
}

}  // namespace hpsf
