#include <algorithm>
#include <array>
#include <cctype>
#include <vector>

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
    case vk::PhysicalDeviceType::eDiscreteGpu: return 0;
    case vk::PhysicalDeviceType::eIntegratedGpu: return 1;
    case vk::PhysicalDeviceType::eVirtualGpu: return 2;
    case vk::PhysicalDeviceType::eOther: return 3;
    default: return 4;
  }
}

std::string TypeName(vk::PhysicalDeviceType type) {
  switch (type) {
    case vk::PhysicalDeviceType::eDiscreteGpu: return "discrete";
    case vk::PhysicalDeviceType::eIntegratedGpu: return "integrated";
    case vk::PhysicalDeviceType::eVirtualGpu: return "virtual";
    case vk::PhysicalDeviceType::eCpu: return "cpu";
    default: return "other";
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
  f.shader_float64 = features.get<vk::PhysicalDeviceFeatures2>().features.shaderFloat64;
  f.buffer_int64_atomics = features.get<vk::PhysicalDeviceVulkan12Features>().shaderBufferInt64Atomics;
  if (HasExtension(physical, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME)) {
    auto atomics = physical.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceShaderAtomicFloatFeaturesEXT>();
    f.buffer_float32_atomic_add = atomics.get<vk::PhysicalDeviceShaderAtomicFloatFeaturesEXT>().shaderBufferFloat32AtomicAdd;
  }
  return info;
}

std::string Join(const std::vector<std::string>& items, const char* separator) {
  std::string s;
  for (const std::string& item : items) s += (s.empty() ? "" : separator) + item;
  return s;
}

}  // namespace

std::string VulkanDeviceInfo::ToString() const {
  return "[ VulkanDevice name: '" + name + "' type: " + type + " driver: '" + driver_name + "' '" + driver_info +
         "' api: " + api_version + " subgroup_size: " + std::to_string(subgroup_size) + " ]";
}

VulkanDevice::VulkanDevice(const std::string& name_filter) {
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

    // Candidates in preference order; the first that has every feature wins.
    std::vector<std::size_t> order;
    std::vector<std::string> seen;
    for (std::size_t i = 0; i < physicals.size(); ++i) {
      std::string name = physicals[i].getProperties().deviceName.data();
      seen.push_back("'" + name + "'");
      if (name_filter.empty() || Lower(name).find(Lower(name_filter)) != std::string::npos) order.push_back(i);
    }
    if (physicals.empty()) {
      throw VulkanUnavailable("no Vulkan device found (install mesa-vulkan-drivers for lavapipe, or check VK_ICD_FILENAMES)");
    }
    if (order.empty()) {
      throw VulkanUnavailable("--vk-device '" + name_filter + "' matches no Vulkan device; available: " + Join(seen, ", "));
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
    auto compute = std::find_if(families.begin(), families.end(),
                                [](const vk::QueueFamilyProperties& q) { return bool(q.queueFlags & vk::QueueFlagBits::eCompute); });
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
    chain.get<vk::PhysicalDeviceFeatures2>().features.shaderFloat64 = true;
    chain.get<vk::PhysicalDeviceVulkan12Features>().shaderBufferInt64Atomics = true;
    chain.get<vk::PhysicalDeviceShaderAtomicFloatFeaturesEXT>().shaderBufferFloat32AtomicAdd = true;
    d.device = vk::raii::Device(d.physical, chain.get<vk::DeviceCreateInfo>());
    d.queue = vk::raii::Queue(d.device, d.queue_family, 0);
    d.command_pool = vk::raii::CommandPool(
        d.device, vk::CommandPoolCreateInfo(vk::CommandPoolCreateFlagBits::eResetCommandBuffer, d.queue_family));
    d.timestamps = vk::raii::QueryPool(d.device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, 2));
    d.timestamp_period_ns = d.physical.getProperties().limits.timestampPeriod;
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
  return kind == BindingKind::kStorageBuffer ? vk::DescriptorType::eStorageBuffer : vk::DescriptorType::eUniformTexelBuffer;
}

}  // namespace

HostBuffer CreateHostBuffer(VulkanDevice::Impl& d, vk::DeviceSize size) {
  HostBuffer b;
  b.size = std::max<vk::DeviceSize>(size, 16);
  b.buffer = vk::raii::Buffer(d.device, vk::BufferCreateInfo({}, b.size,
                                                              vk::BufferUsageFlagBits::eStorageBuffer |
                                                                  vk::BufferUsageFlagBits::eUniformTexelBuffer));
  const vk::MemoryRequirements requirements = b.buffer.getMemoryRequirements();
  const vk::PhysicalDeviceMemoryProperties memory = d.physical.getMemoryProperties();
  const auto wanted = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
  std::uint32_t type = memory.memoryTypeCount;
  for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
    if ((requirements.memoryTypeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted) {
      type = i;
      break;
    }
  }
  if (type == memory.memoryTypeCount) throw VulkanUnavailable("Vulkan device '" + d.info.name + "' has no host-visible coherent memory");
  b.memory = vk::raii::DeviceMemory(d.device, vk::MemoryAllocateInfo(requirements.size, type));
  b.buffer.bindMemory(*b.memory, 0);
  b.mapped = b.memory.mapMemory(0, b.size);
  if (b.size % 16 == 0 && b.size / 16 <= d.physical.getProperties().limits.maxTexelBufferElements) {
    b.texels = vk::raii::BufferView(d.device, vk::BufferViewCreateInfo({}, *b.buffer, vk::Format::eR32G32B32A32Uint, 0, b.size));
  }
  return b;
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

void BindBuffers(VulkanDevice::Impl& d, ComputeProgram& program, std::span<HostBuffer* const> buffers) {
  const vk::DeviceSize storage_range = d.physical.getProperties().limits.maxStorageBufferRange;
  std::vector<vk::DescriptorBufferInfo> infos(buffers.size());
  std::vector<vk::BufferView> views(buffers.size());
  std::vector<vk::WriteDescriptorSet> writes;
  for (std::uint32_t i = 0; i < buffers.size(); ++i) {
    HostBuffer& b = *buffers[i];
    const vk::DescriptorType type = DescriptorType(program.bindings.at(i));
    vk::WriteDescriptorSet write(*program.set, i, 0, 1, type);
    if (program.bindings[i] == BindingKind::kStorageBuffer) {
      if (b.size > storage_range) {
        throw std::length_error("a storage buffer of " + std::to_string(b.size) + " bytes exceeds maxStorageBufferRange (" +
                                std::to_string(storage_range) + ") of '" + d.info.name + "'");
      }
      infos[i] = vk::DescriptorBufferInfo(*b.buffer, 0, b.size);
      write.setBufferInfo(infos[i]);
    } else {
      if (!*b.texels) {
        throw std::length_error("a texel buffer of " + std::to_string(b.size) + " bytes exceeds maxTexelBufferElements of '" +
                                d.info.name + "'");
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
  vk::raii::CommandBuffers buffers(d.device, vk::CommandBufferAllocateInfo(*d.command_pool, vk::CommandBufferLevel::ePrimary, 1));
  vk::raii::CommandBuffer& cb = buffers.front();
  cb.begin(vk::CommandBufferBeginInfo(vk::CommandBufferUsageFlagBits::eOneTimeSubmit));
  cb.resetQueryPool(*d.timestamps, 0, 2);
  cb.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *d.timestamps, 0);
  record(cb);
  cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *d.timestamps, 1);
  cb.end();
  vk::raii::Fence fence(d.device, vk::FenceCreateInfo());
  const vk::CommandBuffer handle = *cb;
  d.queue.submit(vk::SubmitInfo({}, {}, handle), *fence);
  if (d.device.waitForFences(*fence, true, UINT64_MAX) != vk::Result::eSuccess) {
    throw std::runtime_error("Vulkan fence wait failed on '" + d.info.name + "'");
  }
  auto [result, ticks] = d.timestamps.getResults<std::uint64_t>(0, 2, 2 * sizeof(std::uint64_t), sizeof(std::uint64_t),
                                                                  vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
  if (result != vk::Result::eSuccess) return 0.0;
  return double(ticks[1] - ticks[0]) * d.timestamp_period_ns * 1e-6;
}

}  // namespace vulkan_internal
}  // namespace hpsf
