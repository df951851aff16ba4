// transport.comp, or a team's transport shader (--transport-spv, docs/reference/buffer-interface.md), on a Vulkan
// device: several filtered bounces' lookups (core/transport.h) in the device table as the previous frame left it,
// before the frame's accumulate. The host then adds the transported records as it adds any
// record (vulkan_filter.cpp), so the accumulate's interface stays the one a team's shader is written against.
#ifndef HPSF_VULKAN_TRANSPORT_PASS_H
#define HPSF_VULKAN_TRANSPORT_PASS_H

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/key_batch.h"
#include "core/probing.h"
#include "core/record.h"
#include "core/transport.h"
#include "vulkan/vulkan_internal.h"

namespace hpsf {

// The device table the transport reads: the buffers of the stable interface and its shape.
struct TransportTable {
  vulkan_internal::DeviceBuffer& tags;
  vulkan_internal::DeviceBuffer& sums;
  vulkan_internal::DeviceBuffer& counts;
  std::uint32_t accumulation;  // core/shared/table_params.h's kAccumulate*
  int fixed_point_bits;
  std::uint32_t probe_limit;
  ProbeKind probing;
  bool holds_frame;  // false: no table before the frame (a forced first frame), every lookup misses
};

struct DeviceTransport {
  // Per record of records then deeper: its contribution, transported where `read` names a slot.
  std::vector<glm::vec4> contributions;
  std::vector<std::uint32_t> read;  // the slot its scattered vertex's light came from, or kNothingTransported
  TransportStats stats;
  double ms = 0;  // device time of the pass
};

class TransportPass {
 public:
  // custom: a team's SPIR-V, named `name` in errors; empty for transport.comp.
  TransportPass(VulkanDevice::Impl& device, std::span<const std::uint32_t> custom = {}, std::string name = "");

  // records: the frame's records then its deeper ones; scattered: one per record. params: the frame's key
  // parameters (record_count the records with the deeper ones). Every word the shader writes back is checked before
  // it is used: a ShaderOutputError otherwise.
  DeviceTransport Run(std::span<const Record> records, std::span<const Record> scattered, const KeyParams& params,
                      const TransportTable& table);

 private:
  VulkanDevice::Impl& device_;
  std::string name_;  // who writes the words read back, for a ShaderOutputError
  vulkan_internal::ComputeProgram program_;
  vulkan_internal::DeviceBuffer scattered_, marked_, contributions_, read_, stats_;
  std::vector<vulkan_internal::StagingBuffer> staging_;
};

}  // namespace hpsf

#endif  // HPSF_VULKAN_TRANSPORT_PASS_H
