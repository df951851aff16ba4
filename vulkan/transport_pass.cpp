#include "vulkan/transport_pass.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/input_check.h"
#include "core/read_back_check.h"
#include "core/shared/record_layout.h"
#include "transport_spv.h"

namespace hpsf {

using vulkan_internal::BindingKind;
using vulkan_internal::DeviceBuffer;

namespace {

struct TransportPush {
  KeyParams key;
  double unscale;  // 2^-F
  std::uint32_t probe_limit;
  std::uint32_t probe_scheme;
  std::uint32_t accumulation;  // core/shared/table_params.h's kAccumulate*
  std::uint32_t reserved;
};
static_assert(sizeof(TransportPush) == 88, "push constants of transport.comp");

constexpr BindingKind kTransportBindings[] = {BindingKind::kUniformTexelBuffer, BindingKind::kStorageBuffer,
                                              BindingKind::kStorageBuffer,      BindingKind::kStorageBuffer,
                                              BindingKind::kStorageBuffer,      BindingKind::kStorageBuffer,
                                              BindingKind::kStorageBuffer,      BindingKind::kStorageBuffer};
constexpr std::uint32_t kTransportRecordsPerWorkgroup = 64;  // transport.comp's local_size_x

void Ensure(VulkanDevice::Impl& device, DeviceBuffer& buffer, vk::DeviceSize bytes) {
  if (!*buffer.buffer || buffer.size < bytes) buffer = vulkan_internal::CreateDeviceBuffer(device, bytes);
}

}  // namespace

TransportPass::TransportPass(VulkanDevice::Impl& device, std::span<const std::uint32_t> custom, std::string name)
    : device_(device),
      name_(custom.empty() ? "the transport shader" : "the transport shader " + name),
      program_(vulkan_internal::CreateComputeProgram(device, custom.empty() ? transport_spv : custom,
                                                     kTransportBindings, sizeof(TransportPush))) {}

DeviceTransport TransportPass::Run(std::span<const Record> records, std::span<const Record> scattered,
                                   const KeyParams& params, const TransportTable& table) {
  const std::size_t n = records.size();
  DeviceTransport result;
  result.read.assign(n, kNothingTransported);
  result.contributions.resize(n);
  if (n == 0) return result;
  Ensure(device_, scattered_, std::max<vk::DeviceSize>(n * sizeof(Record), 16));
  Ensure(device_, marked_, std::max<vk::DeviceSize>(n * 4, 4));
  Ensure(device_, contributions_, std::max<vk::DeviceSize>(n * sizeof(glm::vec4), 16));
  Ensure(device_, read_, std::max<vk::DeviceSize>(n * 4, 4));
  Ensure(device_, stats_, 8);

  // The host's verdicts, as core/transport.cpp's: a record transports where it and its scattered vertex have
  // vertices and pass the input checks (a shader never sees NaN).
  std::vector<std::uint32_t> marked(n);
  vulkan_internal::Transfer upload(device_, staging_);
  std::memcpy(upload.Upload(scattered_, n * sizeof(Record)), scattered.data(), n * sizeof(Record));
  auto* contributions = static_cast<glm::vec4*>(upload.Upload(contributions_, n * sizeof(glm::vec4)));
  for (std::size_t i = 0; i < n; ++i) {
    const Record& r = records[i];
    const Record& s = scattered[i];
    marked[i] = shared::RecordHasVertex(r) && shared::RecordHasVertex(s) &&
                CheckRecordInputs(r) == InputVerdict::kAccepted && CheckRecordInputs(s) == InputVerdict::kAccepted;
    result.stats.scattered += marked[i];
    contributions[i] = r.contribution;
  }
  std::memcpy(upload.Upload(marked_, n * 4), marked.data(), n * 4);
  upload.Submit();

  DeviceBuffer* const bindings[] = {&scattered_, &marked_,      &contributions_, &table.tags,
                                    &table.sums, &table.counts, &read_,          &stats_};
  vulkan_internal::BindBuffers(device_, program_, bindings);
  const TransportPush push{params,
                           std::ldexp(1.0, -table.fixed_point_bits),
                           table.holds_frame ? table.probe_limit : 0u,
                           SharedProbeKind(table.probing),
                           table.accumulation,
                           0};
  result.ms = vulkan_internal::SubmitAndWait(device_, [&](vk::raii::CommandBuffer& cb) {
    cb.fillBuffer(*stats_.buffer, 0, VK_WHOLE_SIZE, 0);
    const vk::MemoryBarrier cleared(vk::AccessFlagBits::eTransferWrite,
                                    vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, cleared,
                       nullptr, nullptr);
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *program_.pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *program_.layout, 0, *program_.set, nullptr);
    cb.pushConstants<TransportPush>(*program_.layout, vk::ShaderStageFlagBits::eCompute, 0, push);
    cb.dispatch(vulkan_internal::WorkgroupsFor(static_cast<std::uint32_t>(n), kTransportRecordsPerWorkgroup), 1, 1);
  });

  vulkan_internal::Transfer download(device_, staging_);
  const auto* transported = static_cast<const glm::vec4*>(download.Download(contributions_, n * sizeof(glm::vec4)));
  const auto* read = static_cast<const std::uint32_t*>(download.Download(read_, n * 4));
  const auto* unkeyable = static_cast<const std::uint64_t*>(download.Download(stats_, 8));
  download.Submit();
  // Every word came from a shader: a slot below the capacity where the record transports, else nothing.
  std::vector<std::string> faults;
  const std::uint64_t capacity = params.capacity_mask + std::uint64_t(1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t slot = read[i];
    if (slot == kNothingTransported) {
      result.contributions[i] = records[i].contribution;
      continue;
    }
    if (!marked[i] || slot >= capacity) {
      if (faults.size() < 8) {
        faults.push_back("record " + std::to_string(i) + ": transport read " + std::to_string(slot) + ", " +
                         (marked[i] ? "not a slot below the capacity " + std::to_string(capacity)
                                    : "but the record transports nothing"));
      }
      continue;
    }
    result.read[i] = slot;
    result.contributions[i] = transported[i];
    ++result.stats.found;
  }
  if (*unkeyable > result.stats.scattered - result.stats.found) {
    faults.push_back("transport: " + std::to_string(*unkeyable) + " unkeyable scattered vertices, more than the " +
                     std::to_string(result.stats.scattered - result.stats.found) + " it found no cell for");
  }
  if (!faults.empty()) throw ShaderOutputError(name_, std::move(faults));
  result.stats.unkeyable = *unkeyable;
  result.stats.missed = result.stats.scattered - result.stats.found - result.stats.unkeyable;
  return result;
}

}  // namespace hpsf
