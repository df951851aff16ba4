#include <algorithm>
#include <array>
#include <cctype>
#include <optional>
#include <utility>
#include <vector>

#include "core/error.h"
#include "vulkan/driver_pinning.h"
#include "vulkan/vulkan_internal.h"

namespace hpsf {
namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string VersionString(std::uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

bool HasExtension(const vk::raii::PhysicalDevice& physical, const char* name) {
  for (const vk::ExtensionProperties& e : physical.enumerateDeviceExtensionProperties()) {
    if (std::string(e.extensionName.data()) == name) return true;
  }
  return false;
}

int TypeRank(vk::PhysicalDeviceType type) {  // a real GPU first, lavapipe (a CPU device) last
  switch (type) {
    case vk::PhysicalDeviceType::eDiscreteGpu:
      return 0;
    case vk::PhysicalDeviceType::eIntegratedGpu:
      return 1;
    case vk::PhysicalDeviceType::eVirtualGpu:
      return 2;
    case vk::PhysicalDeviceType::eOther:
      return 3;
    default:
      return 4;
  }
}

std::string TypeName(vk::PhysicalDeviceType type) {
  switch (type) {
    case vk::PhysicalDeviceType::eDiscreteGpu:
      return "discrete";
    case vk::PhysicalDeviceType::eIntegratedGpu:
      return "integrated";
    case vk::PhysicalDeviceType::eVirtualGpu:
      return "virtual";
    case vk::PhysicalDeviceType::eCpu:
      return "cpu";
    default:
      return "other";
  }
}

VulkanDeviceInfo Describe(const vk::raii::PhysicalDevice& physical) {
  VulkanDeviceInfo info;
  const vk::PhysicalDeviceProperties base = physical.getProperties();
  info.name = base.deviceName.data();
  info.type = TypeName(base.deviceType);
  info.api_version = VersionString(base.apiVersion);
  DeviceFeatures& f = info.features;
  f.api_version = base.apiVersion;
  f.timestamp_compute = base.limits.timestampComputeAndGraphics;
  if (base.apiVersion < VK_API_VERSION_1_2) return info;

  auto properties = physical.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceVulkan12Properties,
                                            vk::PhysicalDeviceSubgroupProperties>();
  const auto& v12 = properties.get<vk::PhysicalDeviceVulkan12Properties>();
  info.driver_name = v12.driverName.data();
  info.driver_info = v12.driverInfo.data();
  info.subgroup_size = properties.get<vk::PhysicalDeviceSubgroupProperties>().subgroupSize;
  f.rounding_mode_rte_float32 = v12.shaderRoundingModeRTEFloat32;
  f.signed_zero_inf_nan_preserve_float32 = v12.shaderSignedZeroInfNanPreserveFloat32;
  f.rounding_mode_rte_float64 = v12.shaderRoundingModeRTEFloat64;
  f.signed_zero_inf_nan_preserve_float64 = v12.shaderSignedZeroInfNanPreserveFloat64;

  auto features = physical.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features>();
  f.shader_int64 = features.get<vk::PhysicalDeviceFeatures2>().features.shaderInt64;
  f.robust_buffer_access = features.get<vk::PhysicalDeviceFeatures2>().features.robustBufferAccess;
  f.shader_float64 = features.get<vk::PhysicalDeviceFeatures2>().features.shaderFloat64;
  f.buffer_int64_atomics = features.get<vk::PhysicalDeviceVulkan12Features>().shaderBufferInt64Atomics;
  if (HasExtension(physical, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME)) {
    auto atomics = physical.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceShaderAtomicFloatFeaturesEXT>();
    f.buffer_float32_atomic_add =
        atomics.get<vk::PhysicalDeviceShaderAtomicFloatFeaturesEXT>().shaderBufferFloat32AtomicAdd;
  }
  return info;
}

std::string Join(const std::vector<std::string>& items, const char* separator) {
  std::string s;
  for (const std::string& item : items) s += (s.empty() ? "" : separator) + item;
  return s;
}

using MemoryFlags = vk::MemoryPropertyFlagBits;

struct MemoryPreference {
  vk::MemoryPropertyFlags required;
  vk::MemoryPropertyFlags avoided;
};

// The first memory type among `allowed` that satisfies a preference, trying the preferences in order.
std::optional<std::uint32_t> PickMemoryType(const vk::PhysicalDeviceMemoryProperties& memory, std::uint32_t allowed,
                                            std::initializer_list<MemoryPreference> preferences) {
  for (const MemoryPreference& p : preferences) {
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
      const vk::MemoryPropertyFlags flags = memory.memoryTypes[i].propertyFlags;
      if ((allowed & (1u << i)) && (flags & p.required) == p.required && !(flags & p.avoided)) return i;
    }
  }
  return std::nullopt;
}

std::optional<std::uint32_t> KernelMemoryType(const vk::PhysicalDeviceMemoryProperties& memory, std::uint32_t allowed,
                                              bool staged) {
  if (staged)
    return PickMemoryType(memory, allowed,
                          {{MemoryFlags::eDeviceLocal, MemoryFlags::eHostVisible}, {MemoryFlags::eDeviceLocal, {}}});
  const vk::MemoryPropertyFlags mapped = MemoryFlags::eHostVisible | MemoryFlags::eHostCoherent;
  return PickMemoryType(memory, allowed,
                        {{mapped | MemoryFlags::eDeviceLocal | MemoryFlags::eHostCached, {}},
                         {mapped | MemoryFlags::eDeviceLocal, {}},
                         {mapped, {}}});
}

std::optional<std::uint32_t> StagingMemoryType(const vk::PhysicalDeviceMemoryProperties& memory,
                                               std::uint32_t allowed) {
  const vk::MemoryPropertyFlags mapped = MemoryFlags::eHostVisible | MemoryFlags::eHostCoherent;
  return PickMemoryType(memory, allowed,
                        {{mapped | MemoryFlags::eHostCached, MemoryFlags::eDeviceLocal},
                         {mapped | MemoryFlags::eHostCached, {}},
                         {mapped, {}}});
}

// A memory type that kernels reach at full speed and the host reads through its caches: no staging needed.
bool HasUnifiedMemory(const vk::PhysicalDeviceMemoryProperties& memory) {
  return PickMemoryType(memory, ~0u,
                        {{MemoryFlags::eDeviceLocal | MemoryFlags::eHostVisible | MemoryFlags::eHostCached, {}}})
      .has_value();
}

std::string DescribeMemoryType(const vk::PhysicalDeviceMemoryProperties& memory, std::uint32_t type) {
  return "type " + std::to_string(type) + " " + vk::to_string(memory.memoryTypes[type].propertyFlags) + " of heap " +
         std::to_string(memory.memoryTypes[type].heapIndex) + " (" +
         std::to_string(memory.memoryHeaps[memory.memoryTypes[type].heapIndex].size >> 20) + " MiB)";
}

}  // namespace

std::string VulkanDeviceInfo::ToString() const {
  return "[ VulkanDevice name: '" + name + "' type: " + type + " driver: '" + driver_name + "' '" + driver_info +
         "' api: " + api_version + " subgroup_size: " + std::to_string(subgroup_size) + " memory: " + memory + " ]";
}

VulkanDevice::VulkanDevice(const std::string& name_filter, StagingPolicy staging) {
  try {
    impl_ = std::make_unique<Impl>();  // loads the Vulkan loader library
    Impl& d = *impl_;
    const vk::ApplicationInfo application("hpsf", 1, "hpsf", 1, VK_API_VERSION_1_2);
    try {
      d.instance = vk::raii::Instance(d.context, vk::InstanceCreateInfo({}, &application));
    } catch (const vk::SystemError& e) {
      throw VulkanUnavailable(std::string("no Vulkan driver could create an instance (") + e.what() +
                              "); install mesa-vulkan-drivers for lavapipe, or check VK_ICD_FILENAMES");
    }
    vk::raii::PhysicalDevices physicals(d.instance);
    KeepVulkanDriversLoadedUnderSanitizers();

    // Candidates in preference order; the first that has every feature wins.
    std::vector<std::size_t> order;
    std::vector<std::string> seen;
    for (std::size_t i = 0; i < physicals.size(); ++i) {
      std::string name = physicals[i].getProperties().deviceName.data();
      seen.push_back("'" + name + "'");
      if (name_filter.empty() || Lower(name).find(Lower(name_filter)) != std::string::npos) order.push_back(i);
    }
    if (physicals.empty()) {
      throw VulkanUnavailable(
          "no Vulkan device found (install mesa-vulkan-drivers for lavapipe, or check VK_ICD_FILENAMES)");
    }
    if (order.empty()) {
      throw VulkanUnavailable("--vk-device '" + name_filter +
                              "' matches no Vulkan device; available: " + Join(seen, ", "));
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return TypeRank(physicals[a].getProperties().deviceType) < TypeRank(physicals[b].getProperties().deviceType);
    });
    std::vector<std::string> rejections;
    for (std::size_t i : order) {
      VulkanDeviceInfo info = Describe(physicals[i]);
      std::vector<std::string> missing = MissingRequiredFeatures(info.features);
      if (missing.empty()) {
        d.physical = std::move(physicals[i]);
        d.info = std::move(info);
        break;
      }
      rejections.push_back("Vulkan device '" + info.name + "' lacks " + Join(missing, ", "));
    }
    if (!*d.physical) throw VulkanUnavailable(Join(rejections, "; "));

    const auto families = d.physical.getQueueFamilyProperties();
    auto compute = std::find_if(families.begin(), families.end(), [](const vk::QueueFamilyProperties& q) {
      return bool(q.queueFlags & vk::QueueFlagBits::eCompute);
    });
    if (compute == families.end()) throw VulkanUnavailable("Vulkan device '" + d.info.name + "' has no compute queue");
    d.queue_family = static_cast<std::uint32_t>(compute - families.begin());
    if (compute->timestampValidBits == 0) {
      throw VulkanUnavailable("Vulkan device '" + d.info.name + "' has no timestamps on its compute queue");
    }

    const float priority = 1.0f;
    const vk::DeviceQueueCreateInfo queue_info({}, d.queue_family, 1, &priority);
    const std::array<const char*, 1> extensions = {VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME};
    vk::StructureChain<vk::DeviceCreateInfo, vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features,
                       vk::PhysicalDeviceShaderAtomicFloatFeaturesEXT>
        chain;
    chain.get<vk::DeviceCreateInfo>().setQueueCreateInfos(queue_info).setPEnabledExtensionNames(extensions);
    chain.get<vk::PhysicalDeviceFeatures2>().features.shaderInt64 = true;
    // A team's shader that indexes past a buffer reads 0 and writes nowhere, instead of into the host's memory
    // (lavapipe's buffers are host memory): its placement past the table is then a named failure, not a crash.
    chain.get<vk::PhysicalDeviceFeatures2>().features.robustBufferAccess = true;
    chain.get<vk::PhysicalDeviceFeatures2>().features.shaderFloat64 = true;
    chain.get<vk::PhysicalDeviceVulkan12Features>().shaderBufferInt64Atomics = true;
    chain.get<vk::PhysicalDeviceShaderAtomicFloatFeaturesEXT>().shaderBufferFloat32AtomicAdd = true;
    d.device = vk::raii::Device(d.physical, chain.get<vk::DeviceCreateInfo>());
    d.queue = vk::raii::Queue(d.device, d.queue_family, 0);
    d.command_pool = vk::raii::CommandPool(
        d.device, vk::CommandPoolCreateInfo(vk::CommandPoolCreateFlagBits::eResetCommandBuffer, d.queue_family));
    d.timestamps = vk::raii::QueryPool(d.device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, 2));
    d.timestamp_period_ns = d.physical.getProperties().limits.timestampPeriod;

    const vk::PhysicalDeviceMemoryProperties memory = d.physical.getMemoryProperties();
    d.info.staged = staging == StagingPolicy::kAlways || (staging == StagingPolicy::kAuto && !HasUnifiedMemory(memory));
    const std::optional<std::uint32_t> kernel = KernelMemoryType(memory, ~0u, d.info.staged),
                                       host = StagingMemoryType(memory, ~0u);
    if (!kernel || (d.info.staged && !host)) {
      throw VulkanUnavailable("Vulkan device '" + d.info.name + "' has no memory type for " +
                              (!kernel ? "the kernels' buffers" : "staging (host-visible, coherent)") +
                              " with --vk-staging " + ToString(staging));
    }
    d.kernel_memory_type = *kernel;
    d.staging_memory_type = host.value_or(*kernel);
    d.info.memory = d.info.staged
                        ? "staged: kernels in " + DescribeMemoryType(memory, d.kernel_memory_type) + ", staging in " +
                              DescribeMemoryType(memory, d.staging_memory_type)
                        : "mapped: kernels and host share " + DescribeMemoryType(memory, d.kernel_memory_type);
  } catch (const VulkanUnavailable&) {
    throw;
  } catch (const std::exception& e) {
    throw VulkanUnavailable(std::string("Vulkan initialisation failed: ") + e.what());
  }
}

VulkanDevice::~VulkanDevice() = default;

const VulkanDeviceInfo& VulkanDevice::info() const { return impl_->info; }

namespace vulkan_internal {
namespace {

vk::DescriptorType DescriptorType(BindingKind kind) {
  return kind == BindingKind::kStorageBuffer ? vk::DescriptorType::eStorageBuffer
                                             : vk::DescriptorType::eUniformTexelBuffer;
}

}  // namespace

namespace {

// A buffer in the memory type `preferred` names, or the best type the buffer allows when it does not allow that one.
template <typename Buffer>
void Allocate(VulkanDevice::Impl& d, Buffer& b, vk::BufferUsageFlags usage, bool staging) {
  b.buffer = vk::raii::Buffer(d.device, vk::BufferCreateInfo({}, b.size, usage));
  const vk::MemoryRequirements requirements = b.buffer.getMemoryRequirements();
  const std::uint32_t preferred = staging ? d.staging_memory_type : d.kernel_memory_type;
  std::optional<std::uint32_t> type;
  if (requirements.memoryTypeBits & (1u << preferred)) {
    type = preferred;
  } else {
    const vk::PhysicalDeviceMemoryProperties memory = d.physical.getMemoryProperties();
    type = staging ? StagingMemoryType(memory, requirements.memoryTypeBits)
                   : KernelMemoryType(memory, requirements.memoryTypeBits, d.info.staged);
  }
  if (!type)
    throw VulkanUnavailable("Vulkan device '" + d.info.name + "' offers no suitable memory type for a buffer of " +
                            std::to_string(b.size) + " bytes");
  b.memory = vk::raii::DeviceMemory(d.device, vk::MemoryAllocateInfo(requirements.size, *type));
  b.buffer.bindMemory(*b.memory, 0);
}

}  // namespace

DeviceBuffer CreateDeviceBuffer(VulkanDevice::Impl& d, vk::DeviceSize size) {
  DeviceBuffer b;
  b.size = std::max<vk::DeviceSize>(size, 16);
  Allocate(d, b,
           vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer |
               vk::BufferUsageFlagBits::eTransferSrc | vk::BufferUsageFlagBits::eTransferDst |
               vk::BufferUsageFlagBits::eIndirectBuffer,
           false);
  if (!d.info.staged) b.mapped = b.memory.mapMemory(0, b.size);
  if (b.size % 16 == 0 && b.size / 16 <= d.physical.getProperties().limits.maxTexelBufferElements) {
    b.texels = vk::raii::BufferView(d.device,
                                    vk::BufferViewCreateInfo({}, *b.buffer, vk::Format::eR32G32B32A32Uint, 0, b.size));
  }
  return b;
}

StagingBuffer& Transfer::Staging(vk::DeviceSize bytes) {
  if (used_ == pool_.size()) pool_.emplace_back();
  StagingBuffer& s = pool_[used_++];
  if (!*s.buffer || s.size < bytes) {
    s = StagingBuffer{};
    s.size = std::max<vk::DeviceSize>(bytes, 16);
    Allocate(device_, s, vk::BufferUsageFlagBits::eTransferSrc | vk::BufferUsageFlagBits::eTransferDst, true);
    s.mapped = s.memory.mapMemory(0, s.size);
  }
  return s;
}

void* Transfer::Upload(DeviceBuffer& buffer, vk::DeviceSize bytes) {
  bytes_ += bytes;
  if (buffer.mapped) return buffer.mapped;
  StagingBuffer& s = Staging(bytes);
  if (bytes > 0) copies_.push_back({*s.buffer, *buffer.buffer, bytes});
  return s.mapped;
}

const void* Transfer::Download(DeviceBuffer& buffer, vk::DeviceSize bytes) {
  bytes_ += bytes;
  if (buffer.mapped) return buffer.mapped;
  StagingBuffer& s = Staging(bytes);
  if (bytes > 0) copies_.push_back({*buffer.buffer, *s.buffer, bytes});
  return s.mapped;
}

double Transfer::Submit() {
  if (copies_.empty()) return 0.0;
  const double ms = SubmitAndWait(device_, [&](vk::raii::CommandBuffer& cb) {
    for (const Copy& c : copies_) cb.copyBuffer(c.from, c.to, vk::BufferCopy(0, 0, c.bytes));
  });
  copies_.clear();
  return ms;
}

ComputeProgram CreateComputeProgram(VulkanDevice::Impl& d, std::span<const std::uint32_t> spirv,
                                    std::span<const BindingKind> kinds, std::uint32_t push_constant_size) {
  ComputeProgram p;
  p.bindings.assign(kinds.begin(), kinds.end());
  p.push_constant_size = push_constant_size;
  p.module = vk::raii::ShaderModule(d.device, vk::ShaderModuleCreateInfo({}, spirv.size_bytes(), spirv.data()));
  std::vector<vk::DescriptorSetLayoutBinding> bindings;
  std::vector<vk::DescriptorPoolSize> pool_sizes;
  for (std::uint32_t i = 0; i < kinds.size(); ++i) {
    const vk::DescriptorType type = DescriptorType(kinds[i]);
    bindings.emplace_back(i, type, 1, vk::ShaderStageFlagBits::eCompute);
    pool_sizes.emplace_back(type, 1);
  }
  p.set_layout = vk::raii::DescriptorSetLayout(d.device, vk::DescriptorSetLayoutCreateInfo({}, bindings));
  const vk::PushConstantRange push(vk::ShaderStageFlagBits::eCompute, 0, push_constant_size);
  const vk::DescriptorSetLayout set_layout = *p.set_layout;
  p.layout = vk::raii::PipelineLayout(d.device, vk::PipelineLayoutCreateInfo({}, set_layout, push));
  const vk::PipelineShaderStageCreateInfo stage({}, vk::ShaderStageFlagBits::eCompute, *p.module, "main");
  p.pipeline = vk::raii::Pipeline(d.device, nullptr, vk::ComputePipelineCreateInfo({}, stage, *p.layout));
  p.pool = vk::raii::DescriptorPool(
      d.device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, pool_sizes));
  vk::raii::DescriptorSets sets(d.device, vk::DescriptorSetAllocateInfo(*p.pool, set_layout));
  p.set = std::move(sets.front());
  return p;
}

void BindBuffers(VulkanDevice::Impl& d, ComputeProgram& program, std::span<DeviceBuffer* const> buffers) {
  const vk::DeviceSize storage_range = d.physical.getProperties().limits.maxStorageBufferRange;
  std::vector<vk::DescriptorBufferInfo> infos(buffers.size());
  std::vector<vk::BufferView> views(buffers.size());
  std::vector<vk::WriteDescriptorSet> writes;
  for (std::uint32_t i = 0; i < buffers.size(); ++i) {
    DeviceBuffer& b = *buffers[i];
    const vk::DescriptorType type = DescriptorType(program.bindings.at(i));
    vk::WriteDescriptorSet write(*program.set, i, 0, 1, type);
    if (program.bindings[i] == BindingKind::kStorageBuffer) {
      if (b.size > storage_range) {
        throw std::length_error("a storage buffer of " + std::to_string(b.size) +
                                " bytes exceeds maxStorageBufferRange (" + std::to_string(storage_range) + ") of '" +
                                d.info.name + "'");
      }
      infos[i] = vk::DescriptorBufferInfo(*b.buffer, 0, b.size);
      write.setBufferInfo(infos[i]);
    } else {
      if (!*b.texels) {
        throw std::length_error("a texel buffer of " + std::to_string(b.size) +
                                " bytes exceeds maxTexelBufferElements of '" + d.info.name + "'");
      }
      views[i] = *b.texels;
      write.setTexelBufferView(views[i]);
    }
    writes.push_back(write);
  }
  d.device.updateDescriptorSets(writes, nullptr);
}

std::uint32_t WorkgroupsFor(std::uint32_t items, std::uint32_t per_workgroup) {
  constexpr std::uint32_t kMaxWorkgroups = 65535;
  return std::clamp<std::uint32_t>(items / per_workgroup + (items % per_workgroup != 0), 1, kMaxWorkgroups);
}

double SubmitAndWait(VulkanDevice::Impl& d, const std::function<void(vk::raii::CommandBuffer&)>& record) {
  vk::raii::CommandBuffers buffers(d.device,
                                   vk::CommandBufferAllocateInfo(*d.command_pool, vk::CommandBufferLevel::ePrimary, 1));
  vk::raii::CommandBuffer& cb = buffers.front();
  cb.begin(vk::CommandBufferBeginInfo(vk::CommandBufferUsageFlagBits::eOneTimeSubmit));
  cb.resetQueryPool(*d.timestamps, 0, 2);
  // Submission order alone does not make one submission's writes visible to the next, nor to the host.
  const vk::MemoryBarrier earlier(vk::AccessFlagBits::eMemoryWrite,
                                  vk::AccessFlagBits::eMemoryRead | vk::AccessFlagBits::eMemoryWrite);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eAllCommands, vk::PipelineStageFlagBits::eAllCommands, {}, earlier,
                     nullptr, nullptr);
  cb.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *d.timestamps, 0);
  record(cb);
  cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *d.timestamps, 1);
  const vk::MemoryBarrier to_host(vk::AccessFlagBits::eMemoryWrite, vk::AccessFlagBits::eHostRead);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eAllCommands, vk::PipelineStageFlagBits::eHost, {}, to_host, nullptr,
                     nullptr);
  cb.end();
  vk::raii::Fence fence(d.device, vk::FenceCreateInfo());
  const vk::CommandBuffer handle = *cb;
  d.queue.submit(vk::SubmitInfo({}, {}, handle), *fence);
  if (d.device.waitForFences(*fence, true, UINT64_MAX) != vk::Result::eSuccess) {
    throw std::runtime_error("Vulkan fence wait failed on '" + d.info.name + "'");
  }
  auto [result, ticks] =
      d.timestamps.getResults<std::uint64_t>(0, 2, 2 * sizeof(std::uint64_t), sizeof(std::uint64_t),
                                             vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
  if (result != vk::Result::eSuccess) return 0.0;
  return double(ticks[1] - ticks[0]) * d.timestamp_period_ns * 1e-6;
}

}  // namespace vulkan_internal
}  // namespace hpsf
