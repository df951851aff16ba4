#include "vulkan/key_pass.h"

#include <cstring>

#include "core/shared/packed_key.h"
#include "keys_spv.h"
#include "vulkan/vulkan_internal.h"

namespace hpsf {

using vulkan_internal::DeviceBuffer;

namespace {

constexpr std::uint32_t kRecordsPerWorkgroup = 128 * 16;            // keys.comp's local_size_x * kRecordsPerInvocation
constexpr vk::DeviceSize kPackedKeyBytes = 2 * sizeof(glm::uvec4);  // core/shared/packed_key.h

}  // namespace

struct KeyPass::Impl {
  VulkanDevice::Impl& device;
  vulkan_internal::ComputeProgram program;
  DeviceBuffer records;
  DeviceBuffer keys;
  std::vector<vulkan_internal::StagingBuffer> staging;
  std::uint32_t count = 0;
  std::uint32_t key_identity = 0;  // the last dispatch's: the packed keys leave out a full key's high word
};

constexpr vulkan_internal::BindingKind kKeyBindings[] = {vulkan_internal::BindingKind::kUniformTexelBuffer,
                                                         vulkan_internal::BindingKind::kStorageBuffer};

KeyPass::KeyPass(VulkanDevice& device)
    : impl_(new Impl{device.impl(),
                     vulkan_internal::CreateComputeProgram(device.impl(), keys_spv, kKeyBindings, sizeof(KeyParams)),
                     {},
                     {},
                     {},
                     0}) {}

KeyPass::~KeyPass() = default;

void KeyPass::Upload(std::span<const Record> records) {
  Impl& p = *impl_;
  if (records.size() > UINT32_MAX) throw std::length_error("KeyPass: more than 2^32 - 1 records");
  const vk::DeviceSize record_bytes = records.size_bytes(), key_bytes = records.size() * kPackedKeyBytes;
  if (p.records.size < record_bytes || !*p.records.buffer)
    p.records = vulkan_internal::CreateDeviceBuffer(p.device, record_bytes);
  if (p.keys.size < key_bytes || !*p.keys.buffer) p.keys = vulkan_internal::CreateDeviceBuffer(p.device, key_bytes);
  vulkan_internal::Transfer upload(p.device, p.staging);
  if (!records.empty()) std::memcpy(upload.Upload(p.records, record_bytes), records.data(), record_bytes);
  upload.Submit();
  p.count = static_cast<std::uint32_t>(records.size());
  DeviceBuffer* const bindings[] = {&p.records, &p.keys};
  vulkan_internal::BindBuffers(p.device, p.program, bindings);
}

double KeyPass::Dispatch(const KeyParams& params) {
  Impl& p = *impl_;
  KeyParams pushed = params;
  pushed.record_count = p.count;
  p.key_identity = params.key_identity;
  const std::uint32_t groups = vulkan_internal::WorkgroupsFor(p.count, kRecordsPerWorkgroup);
  return vulkan_internal::SubmitAndWait(p.device, [&](vk::raii::CommandBuffer& cb) {
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *p.program.pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *p.program.layout, 0, *p.program.set, nullptr);
    cb.pushConstants<KeyParams>(*p.program.layout, vk::ShaderStageFlagBits::eCompute, 0, pushed);
    cb.dispatch(groups, 1, 1);
  });
}

std::vector<KeyResult> KeyPass::Download() {
  Impl& p = *impl_;
  std::vector<KeyResult> keys(p.count);
  vulkan_internal::Transfer download(p.device, p.staging);
  const auto* packed = static_cast<const glm::uvec4*>(download.Download(p.keys, keys.size() * kPackedKeyBytes));
  download.Submit();
  for (std::size_t i = 0; i < keys.size(); ++i)
    keys[i] = shared::UnpackKey(packed[2 * i], packed[2 * i + 1], p.key_identity);
  return keys;
}

std::vector<KeyResult> KeyPass::Run(std::span<const Record> records, const KeyParams& params) {
  Upload(records);
  Dispatch(params);
  return Download();
}

}  // namespace hpsf
