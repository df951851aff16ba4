#include "verifier/contract/backend_factory.h"

#include <algorithm>
#include <cstdio>

#include "emulated/emulated_backend.h"
#include "reference/reference_backend.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf {
namespace {

std::uint64_t SlotsUsed(const HashTableDump& table) {
  return std::uint64_t(
      std::count_if(table.tags.begin(), table.tags.end(), [](SlotTag tag) { return tag != kEmptyTag; }));
}

// Several filtered bounces (core/transport.h): what the frame's transport looked up.
nlohmann::json ToJson(const TransportStats& t) {
  return {{"scattered", t.scattered}, {"unkeyable", t.unkeyable}, {"found", t.found}, {"missed", t.missed}};
}

double GigabytesPerSecond(std::uint64_t bytes, double ms) { return ms > 0.0 ? double(bytes) / (ms * 1e6) : 0.0; }

nlohmann::json ToJson(const EmulatedRun& run, const EmulatorOptions& options) {
  nlohmann::json j = {{"mode", options.mode == simt::Mode::kFast ? "fast" : "faithful"},
                      {"probe_failures", run.probe_failures},
                      {"fixed64_wraps", run.wraps},
                      {"count_wraps", run.count_wraps},
                      {"slots_used", SlotsUsed(run.table)},
                      {"probe_lengths", run.probe_lengths},
                      {"fixed_point_bits", run.table.fixed_point_bits},
                      {"evicted", run.evicted},
                      {"tombstones", run.tombstones},
                      {"seeded", run.seeded},
                      {"halved", run.halved},
                      {"resolved_at_level", run.resolved_at_level},
                      {"records_searched", run.records_searched},
                      {"neighbours_read", run.neighbours_read},
                      {"transport", ToJson(run.transport)}};
  const EmulatedTimings& t = run.timings;
  j["timings_ms"] = {{"transport", t.transport_ms},     {"keys", t.keys_ms},
                     {"fixed_point", t.fixed_point_ms}, {"clear", t.clear_ms},
                     {"accumulate", t.accumulate_ms},   {"level_seed", t.level_seed_ms},
                     {"compaction", t.compaction_ms},   {"settle", t.settle_ms},
                     {"temporal", t.temporal_ms},       {"eviction", t.eviction_ms},
                     {"read_back", t.read_back_ms},     {"resolve", t.resolve_ms}};
  if (options.mode == simt::Mode::kFaithful) {
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(run.trace_hash));
    j["warp_size"] = options.warp_size;
    j["schedule"] = options.schedule;
    j["trace_hash"] = hash;
    j["steps"] = run.launch.stats.steps;
    j["operations"] = run.launch.stats.operations;
    j["cas_failures"] = run.launch.stats.cas_failures;
    j["conflict_groups"] = run.launch.stats.conflict_groups;
    nlohmann::json lanes = nlohmann::json::object();
    for (const auto& [active, steps] : run.launch.stats.active_lanes) lanes[std::to_string(active)] = steps;
    j["active_lanes_per_step"] = lanes;
  }
  return j;
}

nlohmann::json ToJson(const VulkanRun& run, const VulkanDeviceInfo& device) {
  const VulkanTimings& t = run.timings;
  return {{"device", device.name},
          {"driver", device.driver_name + " (" + device.driver_info + ")"},
          {"accumulate_shader", run.accumulate_shader},
          {"probe_failures", run.probe_failures},
          {"fixed64_wraps", run.wraps},
          {"slots_used", SlotsUsed(run.table)},
          {"probe_lengths", run.probe_lengths},
          {"fixed_point_bits", run.table.fixed_point_bits},
          {"evicted", run.evicted},
          {"tombstones", run.tombstones},
          {"seeded", run.seeded},
          {"halved", run.halved},
          {"resolved_at_level", run.resolved_at_level},
          {"records_searched", run.records_searched},
          {"neighbours_read", run.neighbours_read},
          {"transport", ToJson(run.transport)},
          {"memory", device.memory},
          {"staged", device.staged},
          {"timings_ms",
           {{"upload", t.upload_ms},
            {"upload_copy", t.upload_copy_ms},
            {"transport", t.transport_ms},
            {"accumulate", t.accumulate_ms},
            {"level_seed", t.level_seed_ms},
            {"compaction", t.compaction_ms},
            {"settle", t.settle_ms},
            {"temporal", t.temporal_ms},
            {"eviction", t.eviction_ms},
            {"resolve", t.resolve_ms},
            {"filter", t.FilterMs()},
            {"read_back_copy", t.read_back_copy_ms},
            {"read_back", t.read_back_ms}}},
          {"transfers",
           {{"upload_bytes", t.upload_bytes},
            {"upload_gb_per_s", GigabytesPerSecond(t.upload_bytes, t.UploadMs())},
            {"read_back_bytes", t.read_back_bytes},
            {"read_back_gb_per_s", GigabytesPerSecond(t.read_back_bytes, t.ReadBackMs())}}}};
}

}  // namespace

nlohmann::json ToJson(const FilterStats& s) {
  return {{"records", s.records},
          {"records_with_vertex", s.records_with_vertex},
          {"records_without_vertex", s.records_without_vertex},
          {"unkeyable", s.unkeyable},
          {"rejected_non_finite", s.rejected_non_finite},
          {"rejected_negative", s.rejected_negative},
          {"cells", s.cells},
          {"mean_records_per_cell", s.mean_records_per_cell},
          {"max_records_per_cell", s.max_records_per_cell},
          {"fixed_point_bits", s.fixed_point_bits},
          {"fixed64_wraps", s.fixed_point_wraps},
          {"count_wraps", s.count_wraps},
          {"cells_evicted", s.cells_evicted},
          {"cells_seeded", s.cells_seeded},
          {"cells_halved", s.cells_halved},
          {"resolved_at_level", s.resolved_at_level},
          {"records_searched", s.records_searched},
          {"neighbours_read", s.neighbours_read},
          {"transport", ToJson(s.transport)}};
}

BackendInstance MakeBackend(const BackendInfo& info, const BackendSettings& settings, VulkanDevice* device) {
  BackendInstance instance;
  instance.info = &info;
  switch (info.kind) {
    case BackendKind::kReference: {
      auto reference = std::make_unique<ReferenceBackend>();
      const ReferenceBackend* made = reference.get();
      instance.last_frame_stats = [made] { return ToJson(made->result().stats); };
      instance.backend = std::move(reference);
      break;
    }
    case BackendKind::kEmulated: {
      auto emulated = std::make_unique<EmulatedBackend>(WithDefect(settings.emulator, settings.defect),
                                                        KernelWithDefect(settings.defect));
      const EmulatedBackend* made = emulated.get();
      instance.last_frame_stats = [made] { return ToJson(made->run(), made->options()); };
      instance.backend = std::move(emulated);
      break;
    }
    case BackendKind::kVulkan: {
      if (!device) {
        instance.device = std::make_unique<VulkanDevice>(settings.vulkan.device_filter, settings.vulkan.staging);
        device = instance.device.get();
      }
      auto vulkan = std::make_unique<VulkanBackend>(
          *device, settings.vulkan.accumulate_spv, settings.vulkan.eviction_spv, settings.vulkan.temporal_spv,
          settings.vulkan.resolve_spv, settings.vulkan.compaction_spv, settings.vulkan.transport_spv);
      const VulkanBackend* made = vulkan.get();
      const VulkanDeviceInfo* device_info = &device->info();
      instance.last_frame_stats = [made, device_info] { return ToJson(made->run(), *device_info); };
      instance.backend = std::move(vulkan);
      break;
    }
  }
  return instance;
}

}  // namespace hpsf
