#include "tools/hpsf/backend_options.h"

#include <algorithm>
#include <cstdio>

#include "core/error.h"
#include "emulated/emulated_backend.h"
#include "reference/reference_backend.h"
#include "tools/hpsf/filter_options.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf {

namespace {

std::uint64_t SlotsUsed(const HashTableDump& table) {
  return std::uint64_t(std::count_if(table.tags.begin(), table.tags.end(), [](SlotTag tag) { return tag != kEmptyTag; }));
}

double GigabytesPerSecond(std::uint64_t bytes, double ms) { return ms > 0.0 ? double(bytes) / (ms * 1e6) : 0.0; }

}  // namespace

void CheckBackend(const std::string& backend) {
  if (backend != "reference" && backend != "emulated" && backend != "vulkan") {
    throw ConfigError("--backend", "'" + backend + "' is not available; this build has: reference, emulated, vulkan");
  }
}

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
                      {"seeded", run.seeded}};
  const EmulatedTimings& t = run.timings;
  j["timings_ms"] = {{"keys", 1e3 * t.keys},         {"fixed_point", 1e3 * t.fixed_point},
                     {"clear", 1e3 * t.clear},       {"accumulate", 1e3 * t.accumulate},
                     {"level_seed", 1e3 * t.level_seed}, {"temporal", 1e3 * t.temporal},
                     {"eviction", 1e3 * t.eviction},
                     {"read_back", 1e3 * t.read_back}, {"resolve", 1e3 * t.resolve}};
  if (options.mode == simt::Mode::kFaithful) {
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(run.launch.trace_hash));
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
          {"memory", device.memory},
          {"staged", device.staged},
          {"timings_ms",
           {{"upload", run.timings.upload_ms},
            {"upload_copy", run.timings.upload_copy_ms},
            {"accumulate", run.timings.accumulate_ms},
            {"level_seed", run.timings.level_seed_ms},
            {"temporal", run.timings.temporal_ms},
            {"eviction", run.timings.eviction_ms},
            {"resolve", run.timings.resolve_ms},
            {"filter", run.timings.FilterMs()},
            {"read_back_copy", run.timings.read_back_copy_ms},
            {"read_back", run.timings.read_back_ms}}},
          {"transfers",
           {{"upload_bytes", run.timings.upload_bytes},
            {"upload_gb_per_s", GigabytesPerSecond(run.timings.upload_bytes, run.timings.UploadMs())},
            {"read_back_bytes", run.timings.read_back_bytes},
            {"read_back_gb_per_s", GigabytesPerSecond(run.timings.read_back_bytes, run.timings.ReadBackMs())}}}};
}

BackendInstance MakeBackend(const std::string& backend, const EmulatorOptions& emulator, Defect defect,
                            const VulkanBackendOptions& vulkan) {
  CheckBackend(backend);
  BackendInstance instance;
  instance.emulator = emulator;
  if (backend == "reference") {
    instance.backend = std::make_unique<ReferenceBackend>();
  } else if (backend == "emulated") {
    instance.backend = std::make_unique<EmulatedBackend>(emulator, KernelWithDefect(defect));
  } else {
    instance.device = std::make_unique<VulkanDevice>(vulkan.device_filter, vulkan.staging);
    instance.backend = std::make_unique<VulkanBackend>(*instance.device, vulkan.accumulate_spv, vulkan.eviction_spv);
  }
  return instance;
}

nlohmann::json LastFrameEviction(const BackendInstance& instance) {
  if (const auto* reference = dynamic_cast<const ReferenceBackend*>(instance.backend.get())) {
    return {{"cells_evicted", reference->result().stats.cells_evicted}};
  }
  if (const auto* emulated = dynamic_cast<const EmulatedBackend*>(instance.backend.get())) {
    const EmulatedRun& run = emulated->run();
    return {{"evicted", run.evicted}, {"tombstones", run.tombstones}, {"eviction_s", run.timings.eviction}};
  }
  const VulkanRun& run = dynamic_cast<const VulkanBackend&>(*instance.backend).run();
  return {{"evicted", run.evicted}, {"tombstones", run.tombstones}, {"eviction_s", run.timings.eviction_ms / 1e3}};
}

nlohmann::json LastFrameLevelSeed(const BackendInstance& instance) {
  if (const auto* reference = dynamic_cast<const ReferenceBackend*>(instance.backend.get())) {
    return {{"cells_seeded", reference->result().stats.cells_seeded}};
  }
  if (const auto* emulated = dynamic_cast<const EmulatedBackend*>(instance.backend.get())) {
    return {{"seeded", emulated->run().seeded}, {"level_seed_s", emulated->run().timings.level_seed}};
  }
  const VulkanRun& run = dynamic_cast<const VulkanBackend&>(*instance.backend).run();
  return {{"seeded", run.seeded}, {"level_seed_s", run.timings.level_seed_ms / 1e3}};
}

nlohmann::json LastFrameTemporal(const BackendInstance& instance) {
  if (dynamic_cast<const ReferenceBackend*>(instance.backend.get())) return nlohmann::json::object();
  if (const auto* emulated = dynamic_cast<const EmulatedBackend*>(instance.backend.get())) {
    return {{"temporal_s", emulated->run().timings.temporal}};
  }
  return {{"temporal_s", dynamic_cast<const VulkanBackend&>(*instance.backend).run().timings.temporal_ms / 1e3}};
}

BackendOutput LastFrameOutput(const BackendInstance& instance) {
  BackendOutput out;
  if (const auto* reference = dynamic_cast<const ReferenceBackend*>(instance.backend.get())) {
    out.reference = reference->result();
    out.image = out.reference->image;
    out.stats = ToJson(out.reference->stats);
  } else if (const auto* emulated = dynamic_cast<const EmulatedBackend*>(instance.backend.get())) {
    out.emulated = emulated->run();
    out.image = out.emulated->image;
    out.stats = ToJson(*out.emulated, instance.emulator);
  } else {
    out.vulkan = dynamic_cast<const VulkanBackend&>(*instance.backend).run();
    out.image = out.vulkan->image;
    out.stats = ToJson(*out.vulkan, instance.device->info());
  }
  return out;
}

}  // namespace hpsf
