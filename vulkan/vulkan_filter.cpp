#include "vulkan/vulkan_filter.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>

#include <tbb/parallel_for.h>

#include "accumulate_fixed64_spv.h"
#include "accumulate_float32_spv.h"
#include "accumulate_packed_decimal_spv.h"
#include "compaction_spv.h"
#include "core/count_words.h"
#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "core/footprint.h"
#include "core/huge_pages.h"
#include "core/input_check.h"
#include "core/read_back_check.h"
#include "core/resolve.h"
#include "core/shared/fixed_point.h"
#include "core/shared/table_params.h"
#include "core/temporal.h"
#include "eviction_spv.h"
#include "level_seed_spv.h"
#include "packed_settle_spv.h"
#include "resolve_defer_fixed64_spv.h"
#include "resolve_defer_float32_spv.h"
#include "resolve_defer_packed_decimal_spv.h"
#include "resolve_fixed64_spv.h"
#include "resolve_float32_spv.h"
#include "resolve_packed_decimal_spv.h"
#include "resolve_search_fixed64_spv.h"
#include "resolve_search_float32_spv.h"
#include "resolve_search_packed_decimal_spv.h"
#include "temporal_spv.h"
#include "vulkan/spirv_reflection.h"
#include "vulkan/transport_pass.h"
#include "vulkan/vulkan_internal.h"

namespace hpsf {

using vulkan_internal::BindingKind;
using vulkan_internal::ComputeProgram;
using vulkan_internal::DeviceBuffer;

namespace {

// F's passes over the contributions on all cores (core has no thread pool of its own).
void AllCores(std::size_t n, const std::function<void(std::size_t, std::size_t)>& work) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, std::size_t(1) << 16),
                    [&](const tbb::blocked_range<std::size_t>& range) { work(range.begin(), range.end()); });
}

// Each shader's local_size_x times its kRecordsPerInvocation (kPixelsPerInvocation).
constexpr std::uint32_t kAccumulateRecordsPerWorkgroup = 128 * 16;
constexpr std::uint32_t kResolvePixelsPerWorkgroup = 64 * 16;
constexpr std::uint32_t kResolveSumsBinding = 1;  // resolve.glsl's
// resolve.glsl's DeferredHeader: the listed pixels' count, then the search pass's VkDispatchIndirectCommand.
constexpr vk::DeviceSize kDeferredDispatchOffset = 4;
constexpr std::uint32_t kDeferredHeaderBytes = 16;

struct AccumulatePush {
  KeyParams key;
  shared::TableParams table;
  shared::TemporalParams temporal;
};
static_assert(sizeof(AccumulatePush) == 128, "push constants of table_interface.glsl");

struct EvictionPush {
  std::uint32_t capacity;
  std::uint32_t probe_limit;
  std::uint32_t frame;
  std::uint32_t unseen_frames;
  std::uint32_t sum_words_per_slot;
  std::uint32_t pass;  // 0 evict, 1 reclaim, 2 select (priority, dispatched first, per record)
  std::uint32_t record_count;
  std::uint32_t by_priority;
  std::uint32_t probe_scheme;
  std::uint32_t compacted;      // 1: passes 0 and 1 step the occupied list, dispatched indirectly
  std::uint32_t full_keys;      // 1: 64-bit tags (--key-identity full)
  std::uint32_t packed_counts;  // 1: packed-decimal's 32-bit count words
  std::uint32_t levels;         // --levels: the select pass runs per record and level
  std::uint32_t normal_in_index;
  std::uint32_t square_words_per_slot;  // --second-moments: 2 (fixed64) or 1 (float32); 0 without
  std::uint32_t reserved;
};
static_assert(sizeof(EvictionPush) == 64, "push constants of eviction.comp");
constexpr std::uint32_t kEvictionSlotsPerWorkgroup = 64;

struct TemporalPush {
  shared::TemporalParams temporal;
  std::uint32_t capacity;
  std::uint32_t fixed64;
  std::uint32_t compacted;  // 1: one invocation per entry of the occupied list, dispatched indirectly
  std::uint32_t packed;     // 1 with packed-decimal: 32-bit sums and count words (core/shared/packed_sums.h)
  std::uint32_t squares;    // 1 with --second-moments: the square sums blend too
  std::uint32_t reserved;
};
static_assert(sizeof(TemporalPush) == 48, "push constants of temporal.comp");
constexpr std::uint32_t kTemporalSlotsPerWorkgroup = 64;

struct SettlePush {
  std::uint32_t capacity;
  std::uint32_t compacted;  // 1: one invocation per entry of the occupied list, dispatched indirectly
};
static_assert(sizeof(SettlePush) == 8, "push constants of packed_settle.comp");
constexpr std::uint32_t kSettleSlotsPerWorkgroup = 64;

struct LevelSeedPush {
  std::uint32_t capacity;
  std::uint32_t probe_limit;
  std::uint32_t fingerprint_bits;
  std::uint32_t normal_in_index;
  std::uint32_t shift;
  std::uint32_t fixed64;
  std::uint32_t record_count;
  std::uint32_t probe_scheme;
  std::uint32_t key_identity;
  std::uint32_t packed;  // 1 with packed-decimal: 32-bit sums and count words (core/shared/packed_sums.h)
  std::uint32_t levels;  // --levels: the pass runs over every level's placements (core/shared/levels.h)
  std::uint32_t reserved;
};
static_assert(sizeof(LevelSeedPush) == 48, "push constants of level_seed.comp");
constexpr std::uint32_t kLevelSeedRecordsPerWorkgroup = 64;

struct CompactionPush {
  std::uint32_t pass;  // 0 gather, 1 prune, 2 finish the prune, 3 the indirect dispatch
  std::uint32_t record_count;
  std::uint32_t capacity;
  std::uint32_t full_keys;  // 1: 64-bit tags (--key-identity full)
};
static_assert(sizeof(CompactionPush) == 16, "push constants of compaction.comp");
constexpr std::uint32_t kCompactionItemsPerWorkgroup = 64;
constexpr vk::DeviceSize kOccupiedDispatchOffset = 4;  // compaction.comp's Header: count, then the dispatch
constexpr std::uint32_t kOccupiedHeaderBytes = 20;     // and the prune's next count

struct ResolvePush {
  double unscale;
  std::uint32_t capacity;
  std::uint32_t pixel_count;
  std::uint32_t samples_per_pixel;
  std::uint32_t levels;            // --levels: the placements hold levels words per record, level-major
  std::uint32_t min_count;         // --min-count (core/shared/levels.h)
  std::uint32_t neighbour_search;  // --neighbour-search (core/shared/neighbour_search.h)
  KeyParams key;                   // a searching record's key and position are computed again
  std::uint32_t probe_limit;       // the lookups' window
  std::uint32_t probe_scheme;
  std::uint32_t defer_every_pixel;  // --force-effect neighbour-search: the search pass resolves every pixel
  std::uint32_t reserved;
};
static_assert(sizeof(ResolvePush) == 112, "push constants of resolve.glsl");

// The stable interface: binding i of table_interface.glsl.
constexpr BindingKind kAccumulateBindings[] = {
    BindingKind::kUniformTexelBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer,      BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer,      BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer,      BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer};
constexpr BindingKind kEvictionBindings[] = {
    BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer};
constexpr BindingKind kCompactionBindings[] = {BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
                                               BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
                                               BindingKind::kStorageBuffer, BindingKind::kStorageBuffer};
constexpr BindingKind kLevelSeedBindings[] = {
    BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer};
constexpr BindingKind kTemporalBindings[] = {
    BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer};
constexpr BindingKind kSettleBindings[] = {BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
                                           BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
                                           BindingKind::kStorageBuffer};
constexpr BindingKind kResolveBindings[] = {
    BindingKind::kUniformTexelBuffer, BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer,      BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer,      BindingKind::kStorageBuffer, BindingKind::kStorageBuffer,
    BindingKind::kStorageBuffer,      BindingKind::kStorageBuffer, BindingKind::kStorageBuffer};

// --interpolation's parameters, the resolve's binding 10 (resolve.glsl's InterpolationParams).
struct InterpolationParams {
  double v0;
  double v1;
  double square_unscale;   // 2^-G, fixed64
  std::uint32_t function;  // shared::kInterpolation*: off, step, smooth or path
  std::uint32_t
      own_lights;  // 1: each record's own light is binding 11's (RecordBatch::own_light), not its contribution
};
static_assert(sizeof(InterpolationParams) == 32, "resolve.glsl's binding 10");

// A built-in shader's SPIR-V by accumulation mode.
std::span<const std::uint32_t> ByMode(Accumulation mode, std::span<const std::uint32_t> fixed64,
                                      std::span<const std::uint32_t> float32,
                                      std::span<const std::uint32_t> packed_decimal) {
  return mode == Accumulation::kFixed64 ? fixed64 : mode == Accumulation::kFloat32 ? float32 : packed_decimal;
}

struct CopyOut {
  void* to;
  const void* from;
  std::size_t bytes;
};

void ParallelCopy(const CopyOut& copy) {
  constexpr std::size_t kChunk = std::size_t(1) << 22;
  tbb::parallel_for(std::size_t(0), (copy.bytes + kChunk - 1) / kChunk, [&](std::size_t chunk) {
    const std::size_t begin = chunk * kChunk;
    std::memcpy(static_cast<char*>(copy.to) + begin, static_cast<const char*>(copy.from) + begin,
                std::min(kChunk, copy.bytes - begin));
  });
}

std::uint32_t KeyIdentityWord(KeyIdentity identity) {
  return identity == KeyIdentity::kFull ? shared::kIdentityFull : shared::kIdentityFingerprint;
}

// The tags binding holds 32-bit fingerprints or 64-bit full keys (core/key_identity.h); a dump's tags are 64-bit.
std::size_t TagBytes(KeyIdentity identity) { return identity == KeyIdentity::kFull ? 8 : 4; }

void CopyTagsOut(std::vector<SlotTag>& tags, const void* from, KeyIdentity identity) {
  if (identity == KeyIdentity::kFull) return ParallelCopy({tags.data(), from, tags.size() * sizeof(SlotTag)});
  const auto* words = static_cast<const std::uint32_t*>(from);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tags.size(), std::size_t(1) << 16), [&](const auto& range) {
    std::copy(words + range.begin(), words + range.end(), tags.begin() + std::ptrdiff_t(range.begin()));
  });
}

void CopyTagsIn(void* to, const std::vector<SlotTag>& tags, KeyIdentity identity) {
  if (identity == KeyIdentity::kFull) return std::memcpy(to, tags.data(), tags.size() * sizeof(SlotTag)), void();
  std::copy(tags.begin(), tags.end(), static_cast<std::uint32_t*>(to));  // a fingerprint table's, each below 2^32
}

// Bytes per slot of the sums binding: three 64-bit words (fixed64) or three 32-bit ones; of the counts binding:
// a 64-bit count, or packed-decimal's 32-bit count word (core/shared/packed_sums.h).
std::size_t SumBytesPerSlot(Accumulation accumulation) { return accumulation == Accumulation::kFixed64 ? 24 : 12; }
std::size_t CountBytesPerSlot(Accumulation accumulation) {
  return accumulation == Accumulation::kPackedDecimal ? 4 : 8;
}

std::uint32_t AccumulationWord(Accumulation accumulation) {
  switch (accumulation) {
    case Accumulation::kFixed64:
      return shared::kAccumulateFixed64;
    case Accumulation::kFloat32:
      return shared::kAccumulateFloat32;
    case Accumulation::kPackedDecimal:
      return shared::kAccumulatePackedDecimal;
  }
  return shared::kAccumulateFixed64;
}

// What a shader's sums binding is declared as for each accumulation (spirv_reflection.h's SumsAccumulation).
const char* SumsTypeName(Accumulation accumulation) {
  return accumulation == Accumulation::kFixed64   ? "uint64_t"
         : accumulation == Accumulation::kFloat32 ? "float"
                                                  : "uint";
}

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// A pass over the table's slots (the settle, the temporal blend, evict and reclaim): `program` with `push`, one
// invocation per slot, or with compaction one per entry of the occupied list, dispatched by the indirect arguments
// compaction wrote into the list's header.
template <typename Push>
void DispatchOverSlots(vk::raii::CommandBuffer& cb, const ComputeProgram& program, const Push& push,
                       const DeviceBuffer* occupied_header, std::uint32_t capacity, std::uint32_t slots_per_workgroup) {
  cb.bindPipeline(vk::PipelineBindPoint::eCompute, *program.pipeline);
  cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *program.layout, 0, *program.set, nullptr);
  cb.pushConstants<Push>(*program.layout, vk::ShaderStageFlagBits::eCompute, 0, push);
  if (occupied_header) {
    cb.dispatchIndirect(*occupied_header->buffer, kOccupiedDispatchOffset);
  } else {
    cb.dispatch(vulkan_internal::WorkgroupsFor(capacity, slots_per_workgroup), 1, 1);
  }
}

}  // namespace

struct VulkanFilter::Impl {
  VulkanDevice::Impl& device;
  std::vector<std::uint32_t> custom_accumulate;
  std::string accumulate_name;
  Accumulation custom_accumulation;  // what the user's shader declares its sums as
  std::vector<std::uint32_t> custom_eviction;
  std::string eviction_name;
  std::vector<std::uint32_t> custom_temporal;
  std::string temporal_name;
  std::vector<std::uint32_t> custom_resolve;
  std::string resolve_name;
  Accumulation custom_resolve_accumulation;         // what the user's resolve shader declares its sums as
  std::optional<ComputeProgram> accumulate[3];      // by accumulation mode
  std::optional<ComputeProgram> resolve[3][2];      // by accumulation mode, then without and with the search
  std::optional<ComputeProgram> search_resolve[3];  // the search's second pass (resolve.glsl), by accumulation mode
  std::optional<ComputeProgram> eviction;
  std::optional<ComputeProgram> temporal;
  std::optional<ComputeProgram> level_seed;
  DeviceBuffer records, keys, tags, sums, counts, placements, stats, accepted, pixels, last_seen, evicted, victims;
  DeviceBuffer previous_sums, previous_counts;  // the double buffer of temporal.comp and level_seed.comp
  // --second-moments: the square sums, their double buffer for temporal.comp, and the accumulate's binding 12
  DeviceBuffer squares, previous_squares, square_params;
  DeviceBuffer interpolation_params;                    // the resolve's binding 10
  DeviceBuffer own_lights;                              // the resolve's binding 11 (RecordBatch::own_light)
  DeviceBuffer previous_tags, seeded, seeded_count;     // level_seed.comp's
  DeviceBuffer deferred_pixels, deferred_header;        // the search's list of pixels (resolve.glsl)
  std::vector<vulkan_internal::StagingBuffer> staging;  // kept from run to run, on a staged device
  struct TableShape {
    std::uint32_t capacity;
    Accumulation accumulation;
    KeyIdentity key_identity;
    int fixed_point_bits;
    bool compacted;  // the occupied list and its flags are the table's
    bool second_moments = false;
    int square_bits = 0;
  };
  std::optional<TableShape> table;  // what the device table holds after a Run

  ComputeProgram& Accumulate(Accumulation mode) {
    const int m = static_cast<int>(mode);
    if (!accumulate[m]) {
      std::span<const std::uint32_t> spirv = custom_accumulate;
      if (spirv.empty())
        spirv = ByMode(mode, accumulate_fixed64_spv, accumulate_float32_spv, accumulate_packed_decimal_spv);
      accumulate[m] = vulkan_internal::CreateComputeProgram(device, spirv, kAccumulateBindings, sizeof(AccumulatePush));
    }
    return *accumulate[m];
  }
  // The search's variant only where it searches (effect planning: a pass without it has nothing to skip): its first
  // pass, which lists the pixels for SearchResolve. A team's resolve is one shader for both, and one pass.
  ComputeProgram& Resolve(Accumulation mode, bool search) {
    const int m = static_cast<int>(mode);
    std::optional<ComputeProgram>& program = resolve[m][search ? 1 : 0];
    if (!program) {
      std::span<const std::uint32_t> spirv = custom_resolve;
      if (spirv.empty() && search)
        spirv = ByMode(mode, resolve_defer_fixed64_spv, resolve_defer_float32_spv, resolve_defer_packed_decimal_spv);
      if (spirv.empty()) spirv = ByMode(mode, resolve_fixed64_spv, resolve_float32_spv, resolve_packed_decimal_spv);
      program = vulkan_internal::CreateComputeProgram(device, spirv, kResolveBindings, sizeof(ResolvePush));
    }
    return *program;
  }
  ComputeProgram& SearchResolve(Accumulation mode) {
    std::optional<ComputeProgram>& program = search_resolve[static_cast<int>(mode)];
    if (!program) {
      const std::span<const std::uint32_t> spirv =
          ByMode(mode, resolve_search_fixed64_spv, resolve_search_float32_spv, resolve_search_packed_decimal_spv);
      program = vulkan_internal::CreateComputeProgram(device, spirv, kResolveBindings, sizeof(ResolvePush));
    }
    return *program;
  }
  // A pass's program, created at its first use: a team's SPIR-V where one was given, else the built-in shader.
  ComputeProgram& PassProgram(std::optional<ComputeProgram>& program, const std::vector<std::uint32_t>& custom,
                              std::span<const std::uint32_t> built_in, std::span<const BindingKind> bindings,
                              std::uint32_t push_constant_size) {
    if (!program) {
      program = vulkan_internal::CreateComputeProgram(device, custom.empty() ? built_in : custom, bindings,
                                                      push_constant_size);
    }
    return *program;
  }
  ComputeProgram& Eviction() {
    return PassProgram(eviction, custom_eviction, eviction_spv, kEvictionBindings, sizeof(EvictionPush));
  }
  ComputeProgram& LevelSeedProgram() {
    return PassProgram(level_seed, {}, level_seed_spv, kLevelSeedBindings, sizeof(LevelSeedPush));
  }
  ComputeProgram& Temporal() {
    return PassProgram(temporal, custom_temporal, temporal_spv, kTemporalBindings, sizeof(TemporalPush));
  }
  ComputeProgram& Compaction() {
    return PassProgram(compaction, custom_compaction, compaction_spv, kCompactionBindings, sizeof(CompactionPush));
  }
  ComputeProgram& Settle() { return PassProgram(settle, {}, packed_settle_spv, kSettleBindings, sizeof(SettlePush)); }
  // Who wrote the read-back words, for a ShaderOutputError.
  std::string ShaderNames() const {
    if (custom_accumulate.empty() && custom_eviction.empty() && custom_temporal.empty() && custom_resolve.empty() &&
        custom_compaction.empty() && custom_transport.empty()) {
      return "the built-in shaders";
    }
    std::string names = custom_accumulate.empty() ? "" : "the accumulate shader " + accumulate_name;
    if (!custom_eviction.empty()) names += (names.empty() ? "" : " or ") + ("the eviction shader " + eviction_name);
    if (!custom_temporal.empty()) names += (names.empty() ? "" : " or ") + ("the temporal shader " + temporal_name);
    if (!custom_resolve.empty()) names += (names.empty() ? "" : " or ") + ("the resolve shader " + resolve_name);
    if (!custom_compaction.empty())
      names += (names.empty() ? "" : " or ") + ("the compaction shader " + compaction_name);
    if (!custom_transport.empty()) names += (names.empty() ? "" : " or ") + ("the transport shader " + transport_name);
    return names;
  }
  void Ensure(DeviceBuffer& buffer, vk::DeviceSize bytes) {
    if (!*buffer.buffer || buffer.size < bytes) buffer = vulkan_internal::CreateDeviceBuffer(device, bytes);
  }
  // --compaction occupied-list (compaction.comp): set after the constructor's list of the members above.
  std::vector<std::uint32_t> custom_compaction;
  std::string compaction_name;
  std::optional<ComputeProgram> compaction;
  DeviceBuffer listed, occupied, next_occupied, occupied_header;
  // The tag views each team shader that reads tags uses (spirv_reflection.h), held to --key-identity per run.
  std::vector<TeamTagReader> team_tags;
  // packed-decimal's settle (packed_settle.comp).
  std::optional<ComputeProgram> settle;
  DeviceBuffer halved;
  // Several filtered bounces (transport_pass.h), and the resolve's placements where deeper records follow the
  // frame's at several levels: the resolve reads its records' level-major placements over them alone.
  std::optional<TransportPass> transport;
  DeviceBuffer resolve_placements;

  std::vector<std::uint32_t> custom_transport;  // --transport-spv
  std::string transport_name;

  TransportPass& Transport() {
    if (!transport) transport.emplace(device, custom_transport, transport_name);
    return *transport;
  }
};

VulkanFilter::VulkanFilter(VulkanDevice& device, const std::string& accumulate_spv, const std::string& eviction_spv,
                           const std::string& temporal_spv, const std::string& resolve_spv,
                           const std::string& compaction_spv, const std::string& transport_spv)
    : impl_(new Impl{device.impl(),
                     accumulate_spv.empty() ? std::vector<std::uint32_t>{} : ReadSpirvFile(accumulate_spv),
                     accumulate_spv.empty() ? "built-in" : accumulate_spv,
                     Accumulation::kFixed64,
                     eviction_spv.empty() ? std::vector<std::uint32_t>{} : ReadSpirvFile(eviction_spv),
                     eviction_spv,
                     temporal_spv.empty() ? std::vector<std::uint32_t>{} : ReadSpirvFile(temporal_spv),
                     temporal_spv,
                     resolve_spv.empty() ? std::vector<std::uint32_t>{} : ReadSpirvFile(resolve_spv),
                     resolve_spv,
                     Accumulation::kFixed64,
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {},
                     {}}) {
  if (!impl_->custom_accumulate.empty()) {
    impl_->custom_accumulation = SumsAccumulation(impl_->custom_accumulate, accumulate_spv);
  }
  if (!impl_->custom_resolve.empty()) {
    impl_->custom_resolve_accumulation = SumsAccumulation(impl_->custom_resolve, resolve_spv, kResolveSumsBinding);
  }
  if (!compaction_spv.empty()) {
    impl_->custom_compaction = ReadSpirvFile(compaction_spv);
    impl_->compaction_name = compaction_spv;
  }
  if (!transport_spv.empty()) {
    impl_->custom_transport = ReadSpirvFile(transport_spv);
    impl_->transport_name = transport_spv;
  }
  impl_->team_tags =
      TeamTagReaders({impl_->custom_accumulate, accumulate_spv}, {impl_->custom_eviction, eviction_spv},
                     {impl_->custom_compaction, compaction_spv}, {impl_->custom_transport, transport_spv});
}

VulkanFilter::~VulkanFilter() = default;

void VulkanFilter::LoadTable(const HashTableDump& table) {
  Impl& p = *impl_;
  p.table.reset();
  const bool fixed = table.accumulation == Accumulation::kFixed64;
  const bool packed = table.accumulation == Accumulation::kPackedDecimal;
  const std::size_t slots = table.capacity;
  const std::size_t sum_bytes = slots * SumBytesPerSlot(table.accumulation);
  const std::size_t count_bytes = slots * CountBytesPerSlot(table.accumulation);
  const std::size_t tag_bytes = slots * TagBytes(table.key_identity);
  p.Ensure(p.tags, vk::DeviceSize(tag_bytes));
  p.Ensure(p.sums, vk::DeviceSize(sum_bytes));
  p.Ensure(p.counts, vk::DeviceSize(count_bytes));
  p.Ensure(p.last_seen, vk::DeviceSize(slots) * 4);
  vulkan_internal::Transfer upload(p.device, p.staging);
  CopyTagsIn(upload.Upload(p.tags, tag_bytes), table.tags, table.key_identity);
  if (packed) {
    if (table.frame_counters.size() != slots)
      throw InputError("the packed-decimal table has no frame counter per slot");
    auto* sums = static_cast<std::uint32_t*>(upload.Upload(p.sums, sum_bytes));
    auto* words = static_cast<std::uint32_t*>(upload.Upload(p.counts, count_bytes));
    for (std::size_t s = 0; s < slots; ++s) {
      for (int c = 0; c < 3; ++c) sums[s * 3 + c] = std::uint32_t(table.fixed_sums[s][c]);
    }
    PackCountWords(table.counts, table.frame_counters, {words, slots});
  } else {
    const void* sums =
        fixed ? static_cast<const void*>(table.fixed_sums.data()) : static_cast<const void*>(table.float_sums.data());
    std::memcpy(upload.Upload(p.sums, sum_bytes), sums, sum_bytes);
    std::memcpy(upload.Upload(p.counts, count_bytes), table.counts.data(), count_bytes);
  }
  const std::size_t square_bytes = table.second_moments ? slots * (fixed ? 8 : 4) : 8;
  p.Ensure(p.squares, vk::DeviceSize(square_bytes));
  if (table.second_moments) {
    if ((fixed ? table.fixed_squares.size() : table.float_squares.size()) != slots)
      throw InputError("the table keeps second moments but has no square sum per slot");
    const void* squares = fixed ? static_cast<const void*>(table.fixed_squares.data())
                                : static_cast<const void*>(table.float_squares.data());
    std::memcpy(upload.Upload(p.squares, square_bytes), squares, square_bytes);
  }
  void* last_seen = upload.Upload(p.last_seen, slots * 4);
  if (table.last_seen.size() == slots) {
    std::memcpy(last_seen, table.last_seen.data(), slots * 4);
  } else {
    std::memset(last_seen, 0, slots * 4);
  }
  if (table.compacted) {
    if (table.occupied.size() > slots) throw InputError("the table's occupied list is longer than its slots");
    p.Ensure(p.listed, vk::DeviceSize(slots) * 4);
    p.Ensure(p.occupied, vk::DeviceSize(slots) * 4);
    p.Ensure(p.occupied_header, kOccupiedHeaderBytes);
    auto* listed = static_cast<std::uint32_t*>(upload.Upload(p.listed, slots * 4));
    std::memset(listed, 0, slots * 4);
    for (const std::uint32_t slot : table.occupied) {
      if (slot >= slots) throw InputError("the table's occupied list names slot " + std::to_string(slot));
      listed[slot] = 1;
    }
    std::memcpy(upload.Upload(p.occupied, std::max<std::size_t>(table.occupied.size() * 4, 4)), table.occupied.data(),
                table.occupied.size() * 4);
    const std::uint32_t count = static_cast<std::uint32_t>(table.occupied.size());
    const std::uint32_t header[kOccupiedHeaderBytes / 4] = {count, std::min((count + 63) / 64, 65535u), 1, 1, 0};
    std::memcpy(upload.Upload(p.occupied_header, kOccupiedHeaderBytes), header, kOccupiedHeaderBytes);
  }
  upload.Submit();
  p.table = Impl::TableShape{table.capacity,  table.accumulation,   table.key_identity, table.fixed_point_bits,
                             table.compacted, table.second_moments, table.square_bits};
}

VulkanRun VulkanFilter::Run(const RecordBatch& batch, const FilterConfig& config, bool keep_table,
                            const FrameEffects* effects) {
  CheckBatchShape(batch);
  CheckScatteredShape(batch);
  config.Validate();
  Impl& p = *impl_;
  if (!p.custom_accumulate.empty() && p.custom_accumulation != config.accumulation) {
    throw ConfigError("--accum", p.accumulate_name + " declares its sums (binding 3) as " +
                                     SumsTypeName(p.custom_accumulation) + ": it accumulates " +
                                     ToString(p.custom_accumulation) + ", not " + ToString(config.accumulation));
  }
  if (!p.custom_resolve.empty() && p.custom_resolve_accumulation != config.accumulation) {
    throw ConfigError("--accum", p.resolve_name + " declares its sums (binding 1) as " +
                                     SumsTypeName(p.custom_resolve_accumulation) + ": it resolves " +
                                     ToString(p.custom_resolve_accumulation) + ", not " +
                                     ToString(config.accumulation));
  }
  if (!p.custom_resolve.empty() && config.interpolation.enabled()) {
    throw ConfigError("--interpolation", p.resolve_name +
                                             " is a team's resolve: its interface has no interpolation (the square "
                                             "sums and the rule are hpsf's own resolve's bindings 9 and 10)");
  }
  for (const auto& [spirv, name, binding] :
       {std::tuple{&p.custom_eviction, &p.eviction_name, kEvictionCountsBinding},
        std::tuple{&p.custom_temporal, &p.temporal_name, kTemporalCountsBinding},
        std::tuple{&p.custom_transport, &p.transport_name, kTransportCountsBinding}}) {
    if (config.accumulation == Accumulation::kPackedDecimal && !spirv->empty() &&
        !ReadsCountWords(*spirv, *name, binding)) {
      throw ConfigError("--accum", *name + " reads its counts (binding " + std::to_string(binding) +
                                       ") as uint64_t only: not packed-decimal's 32-bit count words");
    }
  }
  for (const TeamTagReader& team : p.team_tags) {
    if (team.views.Takes(config.key_identity)) continue;
    throw ConfigError("--key-identity",
                      team.name + " declares its tags (binding " + std::to_string(team.binding) + ") as " +
                          (team.views.full ? "uint64_t" : "uint") + " only: it reads " +
                          (team.views.full ? "full keys" : "fingerprints") + ", not the " +
                          (config.key_identity == KeyIdentity::kFull ? "64-bit full keys" : "32-bit fingerprints") +
                          " of --key-identity " + ToString(config.key_identity));
  }
  if (keep_table && !(p.table && p.table->capacity == config.capacity && p.table->accumulation == config.accumulation &&
                      p.table->key_identity == config.key_identity)) {
    throw ConfigError("--capacity", "no device table of this shape to carry on from; start a new sequence");
  }
  const int kept_fixed_point_bits = keep_table ? p.table->fixed_point_bits : 0;
  if (keep_table && p.table->second_moments != config.second_moments) {
    throw ConfigError("--second-moments", "the device table keeps other moments; start a new sequence");
  }
  const int kept_square_bits = keep_table ? p.table->square_bits : 0;
  const bool compacting = config.compaction == Compaction::kOccupiedList;
  if (keep_table && compacting && !p.table->compacted) {
    throw ConfigError("--compaction", "the device table has no occupied list; start a new sequence");
  }
  p.table.reset();  // until this run has written a whole table
  // The table's records: the frame's, then the deeper ones (several filtered bounces), which only the resolve skips.
  const TableRecords table_records(batch);
  const std::span<const Record> all = table_records.all();
  const std::uint32_t n = static_cast<std::uint32_t>(all.size());
  const std::uint32_t resolved = static_cast<std::uint32_t>(batch.records.size());
  const bool fixed = config.accumulation == Accumulation::kFixed64;
  const bool packed = config.accumulation == Accumulation::kPackedDecimal;
  const std::size_t sum_bytes = std::size_t(config.capacity) * SumBytesPerSlot(config.accumulation);
  const std::size_t count_bytes = std::size_t(config.capacity) * CountBytesPerSlot(config.accumulation);
  const vk::DeviceSize storage_range = p.device.physical.getProperties().limits.maxStorageBufferRange;
  if (vk::DeviceSize(config.capacity) * 3 * 8 > storage_range) {
    throw ConfigError("--capacity", std::to_string(config.capacity) + " slots need " +
                                        std::to_string(std::uint64_t(config.capacity) * 24) +
                                        " bytes of sums, more than the " + std::to_string(storage_range) + " bytes '" +
                                        p.device.info.name + "' can bind");
  }
  if (std::uint64_t(all.size()) * config.levels > UINT32_MAX) {
    throw InputError("record batch: " + std::to_string(all.size()) + " records with the deeper ones at " +
                     std::to_string(config.levels) + " levels need more than 2^32 - 1 placements");
  }
  if (vk::DeviceSize(n) * sizeof(KeyResult) > storage_range) {
    throw InputError("record batch: " + std::to_string(n) + " records need " +
                     std::to_string(std::uint64_t(n) * sizeof(KeyResult)) + " bytes of keys, more than the " +
                     std::to_string(storage_range) + " bytes '" + p.device.info.name + "' can bind");
  }

  VulkanRun run;
  run.accumulate_shader = p.accumulate_name;
  HashTableDump& table = run.table;
  table.capacity = config.capacity;
  table.probe_limit = config.probe_limit;
  table.probing = config.probing;
  table.fingerprint_bits = config.fingerprint_bits;
  table.key_identity = config.key_identity;
  table.accumulation = config.accumulation;
  table.levels = config.levels;

  // Upload: the records as they are, and the host's input verdicts (a shader never sees a rejected record),
  // written into the kernels' buffers where the host maps them, else into staging buffers copied over.
  auto start = std::chrono::steady_clock::now();
  p.Ensure(p.records, all.size() * sizeof(Record));
  p.Ensure(p.keys, vk::DeviceSize(n) * sizeof(KeyResult));
  const std::size_t tag_bytes = std::size_t(config.capacity) * TagBytes(config.key_identity);
  p.Ensure(p.tags, vk::DeviceSize(tag_bytes));
  p.Ensure(p.sums, vk::DeviceSize(sum_bytes));
  p.Ensure(p.counts, vk::DeviceSize(count_bytes));
  p.Ensure(p.halved, 8);
  // Level-major: record i's level k placement at k n + i (core/shared/levels.h).
  const std::size_t placement_bytes = std::size_t(n) * config.levels * 4;
  p.Ensure(p.placements, vk::DeviceSize(placement_bytes));
  p.Ensure(p.stats, 16);
  p.Ensure(p.accepted, vk::DeviceSize(n) * 4);
  p.Ensure(p.pixels, vk::DeviceSize(batch.width) * batch.height * 3 * 4);
  // hpsf's own search resolves in two passes, the first listing the pixels for the second (resolve.glsl); a team's
  // resolve is one pass. The list is bound always.
  const bool deferring = config.neighbour_search && p.custom_resolve.empty();
  p.Ensure(p.deferred_pixels, deferring ? vk::DeviceSize(batch.width) * batch.height * 4 : 4);
  p.Ensure(p.deferred_header, kDeferredHeaderBytes);
  const FrameEffects planned = effects ? *effects : PlanFrameEffects(config, keep_table ? kLaterFrame : 0);
  // Last-seen frames are tracked whenever eviction is asked for; the pass runs where the plan says.
  const bool tracking = config.eviction.enabled();
  const bool evicting = planned.eviction;
  p.Ensure(p.last_seen, vk::DeviceSize(config.capacity) * 4);  // bound always (binding 8), written with eviction only
  p.Ensure(p.evicted, 8);
  const bool by_priority = config.eviction.by_priority();
  p.Ensure(p.victims, by_priority ? vk::DeviceSize(config.capacity) * 4 : 4);  // bound with eviction
  // The occupied list (compaction.comp), bound always to the passes over slots, sized for the table with compaction.
  p.Ensure(p.occupied, compacting ? vk::DeviceSize(config.capacity) * 4 : 4);
  p.Ensure(p.occupied_header, kOccupiedHeaderBytes);
  if (compacting) {
    p.Ensure(p.listed, vk::DeviceSize(config.capacity) * 4);
    p.Ensure(p.next_occupied, vk::DeviceSize(config.capacity) * 4);
  }
  const KeyParams key_params =
      MakeKeyParams(config, FootprintScale(config.filter_width_px, batch.fov_y_radians, batch.height), n);

  // Several filtered bounces (vulkan/transport_pass.h): the records' contributions transported from the table as the
  // previous frame left it, before anything of this frame touches it; the records then enter the table as any do.
  std::optional<DeviceTransport> transport;
  if (planned.transport) {
    const TransportTable before{p.tags,
                                p.sums,
                                p.counts,
                                AccumulationWord(config.accumulation),
                                kept_fixed_point_bits,
                                config.probe_limit,
                                config.probing,
                                keep_table};
    transport = batch.scattered.empty() ? DeviceTransport{{}, std::vector<std::uint32_t>(n, kNothingTransported), {}, 0}
                                        : p.Transport().Run(all, batch.scattered, key_params, before);
    run.transport_read = std::move(transport->read);
    run.transport = transport->stats;
    run.timings.transport_ms = transport->ms;
  }
  start = std::chrono::steady_clock::now();
  vulkan_internal::Transfer upload(p.device, p.staging);
  auto* records = static_cast<Record*>(upload.Upload(p.records, all.size() * sizeof(Record)));
  auto* accepted = static_cast<std::uint32_t*>(upload.Upload(p.accepted, vk::DeviceSize(n) * 4));
  // Bound always: a vec4 where the batch has no own lights.
  const vk::DeviceSize own_bytes = std::max<vk::DeviceSize>(batch.own_light.size() * sizeof(glm::vec4), 16);
  p.Ensure(p.own_lights, own_bytes);
  if (!batch.own_light.empty()) {
    std::memcpy(upload.Upload(p.own_lights, own_bytes), batch.own_light.data(), own_bytes);
  }
  std::vector<glm::vec3> entering;  // for F: the contributions of the records that enter the table, else zero
  ResizeOnHugePages(entering, n);
  tbb::parallel_for(
      tbb::blocked_range<std::uint32_t>(0, n, 1 << 14), [&](const tbb::blocked_range<std::uint32_t>& range) {
        std::memcpy(records + range.begin(), all.data() + range.begin(), range.size() * sizeof(Record));
        const auto judge = [&](std::uint32_t i, const Record& r) {
          accepted[i] = CheckRecordInputs(r) == InputVerdict::kAccepted;
          entering[i] = accepted[i] && shared::RecordHasVertex(r) ? glm::vec3(r.contribution) : glm::vec3(0.0f);
        };
        for (std::uint32_t i = range.begin(); i < range.end(); ++i) {
          if (!transport || run.transport_read[i] == kNothingTransported) {
            judge(i, all[i]);
            continue;
          }
          Record transported = all[i];  // judged as it enters the table
          transported.contribution = records[i].contribution = transport->contributions[i];
          judge(i, transported);
        }
      });
  run.timings.upload_ms = MillisecondsSince(start);
  run.timings.upload_copy_ms = upload.Submit();
  run.timings.upload_bytes = upload.bytes();
  table.fixed_point_bits = packed                    ? 0
                           : keep_table              ? kept_fixed_point_bits
                           : config.fixed_point_bits ? *config.fixed_point_bits
                                                     : ChooseFixedPointBitsOf(entering, AllCores, config.SumHeadroom());
  if (config.accumulation == Accumulation::kFloat32) RequireFloat32Range(table.fixed_point_bits);
  if (fixed) RequireFixedPointConverts(entering, table.fixed_point_bits);
  if (packed) RequirePackedDecimalConverts(entering);
  table.second_moments = config.second_moments;
  if (config.second_moments) {
    table.square_bits = keep_table           ? kept_square_bits
                        : config.square_bits ? *config.square_bits
                                             : ChooseSquareBitsOf(entering, AllCores, config.SquareHeadroom());
    if (fixed) RequireSquaresConvert(entering, table.square_bits);
    if (!fixed) RequireFloat32SquaresRange(table.square_bits);
  }
  // Bound always (bindings 11 and 12), sized for the table with --second-moments.
  const std::size_t square_bytes = config.second_moments ? std::size_t(config.capacity) * (fixed ? 8 : 4) : 8;
  p.Ensure(p.squares, vk::DeviceSize(square_bytes));
  p.Ensure(p.previous_squares, config.second_moments && planned.temporal ? vk::DeviceSize(square_bytes) : 8);
  p.Ensure(p.square_params, 8);

  // The double buffer of the temporal blend and the level seed: the table as the previous frame left it, copied
  // before the accumulate (the seed needs its tags too); on a first frame where a pass is forced, an empty table.
  const bool blending = planned.temporal;
  const bool seeding = planned.level_seed;
  const bool double_buffer = blending || seeding;
  const vk::DeviceSize sum_bytes_on_device = sum_bytes;
  // Bound always (bindings 9 and 10 of the stable interface), sized for the table when the frame needs them.
  p.Ensure(p.previous_sums, double_buffer ? sum_bytes_on_device : 8);
  p.Ensure(p.previous_counts, double_buffer ? vk::DeviceSize(count_bytes) : 8);
  if (seeding) {
    p.Ensure(p.previous_tags, vk::DeviceSize(tag_bytes));
    p.Ensure(p.seeded, vk::DeviceSize(config.capacity) * 4);
    p.Ensure(p.seeded_count, 8);
  }

  // Accumulate: clear the table, then 16 records per invocation.
  ComputeProgram& accumulate = p.Accumulate(config.accumulation);
  DeviceBuffer* const accumulate_buffers[] = {
      &p.records,         &p.keys,    &p.tags,         &p.sums,      &p.counts,
      &p.placements,      &p.stats,   &p.accepted,     &p.last_seen, &p.previous_sums,
      &p.previous_counts, &p.squares, &p.square_params};
  vulkan_internal::BindBuffers(p.device, accumulate, accumulate_buffers);
  AccumulatePush push{
      key_params,
      {config.capacity, config.probe_limit, SumScale(config.accumulation, table.fixed_point_bits),
       AccumulationWord(config.accumulation), config.frame, tracking ? 1u : 0u, blending ? 1u : 0u,
       by_priority ? 1u : 0u, SharedProbeKind(config.probing), config.levels},
      MakeTemporalParams(config.temporal, config.accumulation, table.fixed_point_bits, table.square_bits)};
  const std::array<std::int32_t, 2> square_params{config.second_moments ? 1 : 0, table.square_bits};
  const bool double_squares = config.second_moments && blending;
  run.timings.accumulate_ms = vulkan_internal::SubmitAndWait(p.device, [&](vk::raii::CommandBuffer& cb) {
    cb.fillBuffer(*p.stats.buffer, 0, VK_WHOLE_SIZE, 0);
    cb.updateBuffer<std::int32_t>(*p.square_params.buffer, 0, square_params);
    if (double_squares && keep_table) {
      cb.copyBuffer(*p.squares.buffer, *p.previous_squares.buffer, vk::BufferCopy(0, 0, square_bytes));
    } else if (double_squares) {
      cb.fillBuffer(*p.previous_squares.buffer, 0, VK_WHOLE_SIZE, 0);
    }
    if (seeding) {
      if (keep_table) {
        cb.copyBuffer(*p.tags.buffer, *p.previous_tags.buffer, vk::BufferCopy(0, 0, tag_bytes));
      } else {
        cb.fillBuffer(*p.previous_tags.buffer, 0, VK_WHOLE_SIZE, 0);
      }
      cb.fillBuffer(*p.seeded.buffer, 0, VK_WHOLE_SIZE, 0);
      cb.fillBuffer(*p.seeded_count.buffer, 0, VK_WHOLE_SIZE, 0);
    }
    if (double_buffer && keep_table) {
      cb.copyBuffer(*p.sums.buffer, *p.previous_sums.buffer, vk::BufferCopy(0, 0, sum_bytes_on_device));
      cb.copyBuffer(*p.counts.buffer, *p.previous_counts.buffer, vk::BufferCopy(0, 0, vk::DeviceSize(count_bytes)));
    } else if (double_buffer) {
      for (DeviceBuffer* cleared : {&p.previous_sums, &p.previous_counts})
        cb.fillBuffer(*cleared->buffer, 0, VK_WHOLE_SIZE, 0);
    }
    if (!keep_table) {
      for (DeviceBuffer* cleared : {&p.tags, &p.sums, &p.counts, &p.squares})
        cb.fillBuffer(*cleared->buffer, 0, VK_WHOLE_SIZE, 0);
      if (tracking) cb.fillBuffer(*p.last_seen.buffer, 0, VK_WHOLE_SIZE, 0);
      if (compacting) {  // the lists too, so that an entry a broken count exposes is the same on every run
        for (DeviceBuffer* cleared : {&p.listed, &p.occupied_header, &p.occupied, &p.next_occupied})
          cb.fillBuffer(*cleared->buffer, 0, VK_WHOLE_SIZE, 0);
      }
    }
    const vk::MemoryBarrier cleared(vk::AccessFlagBits::eTransferWrite,
                                    vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, cleared,
                       nullptr, nullptr);
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *accumulate.pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *accumulate.layout, 0, *accumulate.set, nullptr);
    cb.pushConstants<AccumulatePush>(*accumulate.layout, vk::ShaderStageFlagBits::eCompute, 0, push);
    cb.dispatch(vulkan_internal::WorkgroupsFor(n, kAccumulateRecordsPerWorkgroup), 1, 1);
  });

  // The level seed (level_seed.comp), one invocation per record: a slot new this frame takes its cell's seed from
  // the previous table (copied before the accumulate).
  if (seeding) {
    ComputeProgram& level_seed = p.LevelSeedProgram();
    DeviceBuffer* const seed_buffers[] = {
        &p.keys,          &p.placements,      &p.sums,   &p.counts,      &p.previous_tags,
        &p.previous_sums, &p.previous_counts, &p.seeded, &p.seeded_count};
    vulkan_internal::BindBuffers(p.device, level_seed, seed_buffers);
    const LevelSeedPush seed_push{config.capacity,
                                  config.probe_limit,
                                  config.fingerprint_bits,
                                  config.normal_in_index ? 1u : 0u,
                                  config.level_seed.shift,
                                  fixed ? 1u : 0u,
                                  n,
                                  SharedProbeKind(config.probing),
                                  KeyIdentityWord(config.key_identity),
                                  packed ? 1u : 0u,
                                  config.levels,
                                  0};
    run.timings.level_seed_ms = vulkan_internal::SubmitAndWait(p.device, [&](vk::raii::CommandBuffer& cb) {
      const vk::MemoryBarrier accumulated(vk::AccessFlagBits::eShaderWrite,
                                          vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {},
                         accumulated, nullptr, nullptr);
      cb.bindPipeline(vk::PipelineBindPoint::eCompute, *level_seed.pipeline);
      cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *level_seed.layout, 0, *level_seed.set, nullptr);
      cb.pushConstants<LevelSeedPush>(*level_seed.layout, vk::ShaderStageFlagBits::eCompute, 0, seed_push);
      cb.dispatch(vulkan_internal::WorkgroupsFor(n * config.levels, kLevelSeedRecordsPerWorkgroup), 1, 1);
    });
  }

  // Compaction (compaction.comp): the gather lists the slots records were placed in that are not listed yet, then
  // one invocation writes the indirect dispatch of the passes over the list.
  const vk::MemoryBarrier to_indirect(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eShaderRead |
                                                                            vk::AccessFlagBits::eShaderWrite |
                                                                            vk::AccessFlagBits::eIndirectCommandRead);
  const vk::PipelineStageFlags indirect_stages =
      vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eDrawIndirect;
  DeviceBuffer* const compaction_buffers[] = {&p.placements,      &p.tags,         &p.listed, &p.occupied,
                                              &p.occupied_header, &p.next_occupied};
  // The gather walks every level's placements (core/shared/levels.h): its record_count is the placement words.
  const std::uint32_t placement_words = n * config.levels;
  CompactionPush compaction_push{0, placement_words, config.capacity,
                                 config.key_identity == KeyIdentity::kFull ? 1u : 0u};
  const auto compaction_pass = [&](vk::raii::CommandBuffer& cb, ComputeProgram& compaction, std::uint32_t pass) {
    compaction_push.pass = pass;
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *compaction.pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *compaction.layout, 0, *compaction.set, nullptr);
    cb.pushConstants<CompactionPush>(*compaction.layout, vk::ShaderStageFlagBits::eCompute, 0, compaction_push);
    if (pass == 0) {
      cb.dispatch(vulkan_internal::WorkgroupsFor(placement_words, kCompactionItemsPerWorkgroup), 1, 1);
    } else if (pass == 1) {
      cb.dispatchIndirect(*p.occupied_header.buffer, kOccupiedDispatchOffset);
    } else {
      cb.dispatch(1, 1, 1);
    }
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, indirect_stages, {}, to_indirect, nullptr, nullptr);
  };
  if (compacting) {
    ComputeProgram& compaction = p.Compaction();
    vulkan_internal::BindBuffers(p.device, compaction, compaction_buffers);
    run.timings.compaction_ms = vulkan_internal::SubmitAndWait(p.device, [&](vk::raii::CommandBuffer& cb) {
      const vk::MemoryBarrier accumulated(vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferWrite,
                                          vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer,
                         vk::PipelineStageFlagBits::eComputeShader, {}, accumulated, nullptr, nullptr);
      compaction_pass(cb, compaction, 0);
      compaction_pass(cb, compaction, 3);
    });
  }

  // The passes over slots step the occupied list's entries instead, with compaction.
  const DeviceBuffer* const listed = compacting ? &p.occupied_header : nullptr;

  // The temporal blend (temporal.comp): the table was copied into the previous one before the accumulate, then
  // each slot the frame added to that held samples before is blended. The first frame has nothing to blend.
  if (blending) {
    ComputeProgram& temporal = p.Temporal();
    DeviceBuffer* const temporal_buffers[] = {&p.sums,     &p.counts,          &p.previous_sums, &p.previous_counts,
                                              &p.occupied, &p.occupied_header, &p.squares,       &p.previous_squares};
    vulkan_internal::BindBuffers(p.device, temporal, temporal_buffers);
    const TemporalPush temporal_push{
        MakeTemporalParams(config.temporal, config.accumulation, table.fixed_point_bits, table.square_bits),
        config.capacity,
        fixed ? 1u : 0u,
        compacting ? 1u : 0u,
        packed ? 1u : 0u,
        config.second_moments ? 1u : 0u,
        0};
    run.timings.temporal_ms = vulkan_internal::SubmitAndWait(p.device, [&](vk::raii::CommandBuffer& cb) {
      const vk::MemoryBarrier accumulated(vk::AccessFlagBits::eShaderWrite,
                                          vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {},
                         accumulated, nullptr, nullptr);
      DispatchOverSlots(cb, temporal, temporal_push, listed, config.capacity, kTemporalSlotsPerWorkgroup);
    });
  }

  // packed-decimal's settle (packed_settle.comp), one invocation per slot or list entry, after every add landed and
  // after the blend, which reads the frame's adds as differences the halving would break.
  if (packed) {
    ComputeProgram& settle = p.Settle();
    DeviceBuffer* const settle_buffers[] = {&p.sums, &p.counts, &p.halved, &p.occupied, &p.occupied_header};
    vulkan_internal::BindBuffers(p.device, settle, settle_buffers);
    const SettlePush settle_push{config.capacity, compacting ? 1u : 0u};
    run.timings.settle_ms = vulkan_internal::SubmitAndWait(p.device, [&](vk::raii::CommandBuffer& cb) {
      cb.fillBuffer(*p.halved.buffer, 0, VK_WHOLE_SIZE, 0);
      const vk::MemoryBarrier accumulated(vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferWrite,
                                          vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer,
                         vk::PipelineStageFlagBits::eComputeShader, {}, accumulated, nullptr, nullptr);
      DispatchOverSlots(cb, settle, settle_push, listed, config.capacity, kSettleSlotsPerWorkgroup);
    });
  }

  // Eviction: with priority, select the victims, one invocation per record; then evict and reclaim, one invocation
  // per slot (eviction.comp). The frame's resolve reads only slots the frame touched, which no policy evicts, so
  // it may follow.
  if (evicting) {
    ComputeProgram& eviction = p.Eviction();
    DeviceBuffer* const eviction_buffers[] = {&p.tags,   &p.sums,       &p.counts,  &p.last_seen, &p.evicted,
                                              &p.keys,   &p.placements, &p.victims, &p.occupied,  &p.occupied_header,
                                              &p.squares};
    vulkan_internal::BindBuffers(p.device, eviction, eviction_buffers);
    EvictionPush eviction_push{config.capacity,
                               config.probe_limit,
                               config.frame,
                               config.eviction.unseen_frames,
                               fixed ? 6u : 3u,
                               0,
                               n,
                               by_priority ? 1u : 0u,
                               SharedProbeKind(config.probing),
                               compacting ? 1u : 0u,
                               config.key_identity == KeyIdentity::kFull ? 1u : 0u,
                               packed ? 1u : 0u,
                               config.levels,
                               config.normal_in_index ? 1u : 0u,
                               config.second_moments ? (fixed ? 2u : 1u) : 0u,
                               0};
    run.timings.eviction_ms = vulkan_internal::SubmitAndWait(p.device, [&](vk::raii::CommandBuffer& cb) {
      cb.fillBuffer(*p.evicted.buffer, 0, VK_WHOLE_SIZE, 0);
      cb.fillBuffer(*p.victims.buffer, 0, VK_WHOLE_SIZE, 0);
      const vk::MemoryBarrier cleared(vk::AccessFlagBits::eTransferWrite,
                                      vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, cleared,
                         nullptr, nullptr);
      const std::vector<std::uint32_t> passes =
          by_priority ? std::vector<std::uint32_t>{2u, 0u, 1u} : std::vector<std::uint32_t>{0u, 1u};
      for (std::uint32_t pass : passes) {
        eviction_push.pass = pass;
        // The select pass steps the records, never the list.
        DispatchOverSlots(cb, eviction, eviction_push, pass == 2u ? nullptr : listed,
                          pass == 2u ? n * config.levels : config.capacity, kEvictionSlotsPerWorkgroup);
        // The evict pass reads the victims the select pass marked, the reclaim the counts the evict pass wrote.
        const vk::MemoryBarrier evicted(vk::AccessFlagBits::eShaderWrite,
                                        vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
        cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {},
                           evicted, nullptr, nullptr);
      }
      // The prune drops the slots the reclaim emptied from the list; its count becomes the list's.
      if (compacting) {
        for (std::uint32_t pass : {1u, 2u, 3u}) compaction_pass(cb, p.Compaction(), pass);
      }
    });
    if (compacting) std::swap(p.occupied, p.next_occupied);
  }

  // Resolve: a separate pass, 16 pixels per invocation; with the search, a second pass over the pixels the first
  // listed, one per invocation, dispatched by the first.
  ComputeProgram& resolve = p.Resolve(config.accumulation, config.neighbour_search);
  // With deeper records at several levels, the frame's records' placements copied out level by level
  // (core/shared/levels.h): the resolve's interface places level k of record i at k * records + i.
  const bool separate_placements = resolved != n && config.levels > 1;
  if (separate_placements) p.Ensure(p.resolve_placements, vk::DeviceSize(resolved) * config.levels * 4);
  // --interpolation: the squares (binding 9) and the rule (binding 10), bound always.
  p.Ensure(p.interpolation_params, sizeof(InterpolationParams));
  const InterpolationParams interpolation{config.interpolation.v0, config.interpolation.v1,
                                          std::ldexp(1.0, -table.square_bits), config.interpolation.function,
                                          batch.own_light.empty() ? 0u : 1u};
  DeviceBuffer* const resolve_buffers[] = {&p.records,
                                           &p.sums,
                                           &p.counts,
                                           separate_placements ? &p.resolve_placements : &p.placements,
                                           &p.accepted,
                                           &p.pixels,
                                           &p.tags,
                                           &p.deferred_pixels,
                                           &p.deferred_header,
                                           &p.squares,
                                           &p.interpolation_params,
                                           &p.own_lights};
  vulkan_internal::BindBuffers(p.device, resolve, resolve_buffers);
  ComputeProgram* const search_resolve = deferring ? &p.SearchResolve(config.accumulation) : nullptr;
  if (search_resolve) vulkan_internal::BindBuffers(p.device, *search_resolve, resolve_buffers);
  const std::uint32_t pixel_count = batch.width * batch.height;
  const ResolvePush resolve_push{std::ldexp(1.0, -table.fixed_point_bits),
                                 config.capacity,
                                 pixel_count,
                                 batch.samples_per_pixel,
                                 config.levels,
                                 config.min_count,
                                 config.neighbour_search ? 1u : 0u,
                                 push.key,
                                 config.probe_limit,
                                 SharedProbeKind(config.probing),
                                 planned.search_every_pixel ? 1u : 0u,
                                 0};
  run.timings.resolve_ms = vulkan_internal::SubmitAndWait(p.device, [&](vk::raii::CommandBuffer& cb) {
    cb.updateBuffer<InterpolationParams>(*p.interpolation_params.buffer, 0, interpolation);
    const vk::MemoryBarrier updated(vk::AccessFlagBits::eTransferWrite, vk::AccessFlagBits::eShaderRead);
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, updated,
                       nullptr, nullptr);
    if (separate_placements) {
      std::vector<vk::BufferCopy> levels;
      for (std::uint32_t k = 0; k < config.levels; ++k)
        levels.emplace_back(vk::DeviceSize(k) * n * 4, vk::DeviceSize(k) * resolved * 4, vk::DeviceSize(resolved) * 4);
      const vk::MemoryBarrier placed(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eTransferRead);
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {}, placed,
                         nullptr, nullptr);
      cb.copyBuffer(*p.placements.buffer, *p.resolve_placements.buffer, levels);
      const vk::MemoryBarrier copied(vk::AccessFlagBits::eTransferWrite, vk::AccessFlagBits::eShaderRead);
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, copied,
                         nullptr, nullptr);
    }
    if (search_resolve) {  // no pixel listed, and a dispatch of (0, 1, 1)
      cb.fillBuffer(*p.deferred_header.buffer, 0, 8, 0);
      cb.fillBuffer(*p.deferred_header.buffer, 8, 8, 1);
      const vk::MemoryBarrier filled(vk::AccessFlagBits::eTransferWrite,
                                     vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, filled,
                         nullptr, nullptr);
    }
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *resolve.pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *resolve.layout, 0, *resolve.set, nullptr);
    cb.pushConstants<ResolvePush>(*resolve.layout, vk::ShaderStageFlagBits::eCompute, 0, resolve_push);
    cb.dispatch(vulkan_internal::WorkgroupsFor(pixel_count, kResolvePixelsPerWorkgroup), 1, 1);
    if (search_resolve) {
      const vk::MemoryBarrier listed(vk::AccessFlagBits::eShaderWrite,
                                     vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eIndirectCommandRead);
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                         vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eDrawIndirect, {},
                         listed, nullptr, nullptr);
      cb.bindPipeline(vk::PipelineBindPoint::eCompute, *search_resolve->pipeline);
      cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *search_resolve->layout, 0, *search_resolve->set, nullptr);
      cb.pushConstants<ResolvePush>(*search_resolve->layout, vk::ShaderStageFlagBits::eCompute, 0, resolve_push);
      cb.dispatchIndirect(*p.deferred_header.buffer, kDeferredDispatchOffset);
    }
  });

  // Read-back, into arrays on huge pages in parallel chunks, from the mapped buffers or from staging buffers
  // the device copied them into.
  const std::size_t pixel_bytes = std::size_t(pixel_count) * 3 * sizeof(float);
  vulkan_internal::Transfer download(p.device, p.staging);
  const void* from_pixels = download.Download(p.pixels, pixel_bytes);
  const void* from_keys = download.Download(p.keys, std::size_t(n) * sizeof(KeyResult));
  const void* from_placements = download.Download(p.placements, placement_bytes);
  const void* from_tags = download.Download(p.tags, tag_bytes);
  const void* from_counts = download.Download(p.counts, count_bytes);
  const void* from_sums = download.Download(p.sums, sum_bytes);
  const void* from_stats = download.Download(p.stats, 16);
  const void* from_squares = config.second_moments ? download.Download(p.squares, square_bytes) : nullptr;
  const void* from_last_seen = tracking ? download.Download(p.last_seen, std::size_t(config.capacity) * 4) : nullptr;
  const void* from_evicted = evicting ? download.Download(p.evicted, 8) : nullptr;
  const void* from_seeded = seeding ? download.Download(p.seeded_count, 8) : nullptr;
  const void* from_halved = packed ? download.Download(p.halved, 8) : nullptr;
  const void* from_header = compacting ? download.Download(p.occupied_header, kOccupiedHeaderBytes) : nullptr;
  const void* from_occupied = compacting ? download.Download(p.occupied, std::size_t(config.capacity) * 4) : nullptr;
  run.timings.read_back_copy_ms = download.Submit();
  run.timings.read_back_bytes = download.bytes();
  start = std::chrono::steady_clock::now();
  run.image = Image(batch.width, batch.height);
  ResizeOnHugePages(run.keys, n);
  ResizeOnHugePages(run.placements, n);
  run.coarser_placements.resize(std::size_t(n) * (config.levels - 1));
  ResizeOnHugePages(table.tags, config.capacity);
  ResizeOnHugePages(table.counts, config.capacity);
  if (fixed || packed) {
    ResizeOnHugePages(table.fixed_sums, config.capacity);
  } else {
    ResizeOnHugePages(table.float_sums, config.capacity);
  }
  const auto copies = {
      CopyOut{run.image.pixels.data(), from_pixels, pixel_bytes},
      CopyOut{run.keys.data(), from_keys, std::size_t(n) * sizeof(KeyResult)},
      CopyOut{run.placements.data(), from_placements, std::size_t(n) * 4},
      CopyOut{run.coarser_placements.data(), static_cast<const char*>(from_placements) + std::size_t(n) * 4,
              run.coarser_placements.size() * 4},
      CopyOut{&run.wraps, from_stats, 8},
      CopyOut{&run.count_wraps, static_cast<const char*>(from_stats) + 8, 8}};
  for (const CopyOut& copy : copies) ParallelCopy(copy);
  if (packed) {  // 32-bit words, widened; the count word split into its count and frame counter
    table.frame_counters.resize(config.capacity);
    const auto* sums = static_cast<const std::uint32_t*>(from_sums);
    const auto* words = static_cast<const std::uint32_t*>(from_counts);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, config.capacity, std::size_t(1) << 16),
                      [&](const auto& range) {
                        for (std::size_t s = range.begin(); s < range.end(); ++s) {
                          for (int c = 0; c < 3; ++c) table.fixed_sums[s][c] = sums[s * 3 + c];
                        }
                        const std::size_t n = range.end() - range.begin();
                        SplitCountWords({words + range.begin(), n}, {table.counts.data() + range.begin(), n},
                                        {table.frame_counters.data() + range.begin(), n});
                      });
    std::memcpy(&run.halved, from_halved, 8);
  } else {
    ParallelCopy({table.counts.data(), from_counts, count_bytes});
    ParallelCopy({fixed ? static_cast<void*>(table.fixed_sums.data()) : static_cast<void*>(table.float_sums.data()),
                  from_sums, sum_bytes});
  }
  CopyTagsOut(table.tags, from_tags, config.key_identity);
  table.fixed_squares.clear();
  table.float_squares.clear();
  if (config.second_moments) {
    fixed ? table.fixed_squares.resize(config.capacity) : table.float_squares.resize(config.capacity);
    ParallelCopy(
        {fixed ? static_cast<void*>(table.fixed_squares.data()) : static_cast<void*>(table.float_squares.data()),
         from_squares, square_bytes});
  }
  if (seeding) std::memcpy(&run.seeded, from_seeded, 8);
  if (evicting) std::memcpy(&run.evicted, from_evicted, 8);
  if (compacting) {
    // The count as the shaders left it, at most the list's length: the checker judges the entries.
    std::uint32_t count = 0;
    std::memcpy(&count, from_header, 4);
    const auto* entries = static_cast<const std::uint32_t*>(from_occupied);
    table.compacted = true;
    table.occupied.assign(entries, entries + std::min(count, config.capacity));
  }
  if (tracking) {
    ResizeOnHugePages(table.last_seen, config.capacity);
    ParallelCopy({table.last_seen.data(), from_last_seen, std::size_t(config.capacity) * 4});
  }
  run.timings.read_back_ms = MillisecondsSince(start);
  // Every word came from a shader, perhaps a team's: checked before any is used as an index.
  FinishReadBack(run, config.frame, p.ShaderNames());
  CountCoarserProbes(run, push.key);
  run.min_count = config.min_count;
  run.neighbour_search = config.neighbour_search;
  run.interpolation = config.interpolation;
  run.own_light = batch.own_light;
  run.key_params = push.key;
  CountResolvedLevels(run);
  CountSearches(run, batch);
  p.table = Impl::TableShape{config.capacity, config.accumulation,   config.key_identity, table.fixed_point_bits,
                             compacting,      config.second_moments, table.square_bits};
  return run;
}

}  // namespace hpsf
