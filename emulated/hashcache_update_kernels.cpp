#include "emulated/hashcache_update_kernels.h"

#include <algorithm>
#include <array>
#include <bit>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/shared/cuckoo.h"
#include "core/shared/fixed_point.h"
#include "core/shared/hashcache_cell.h"

namespace hpsf {

// A segment's running sums: fixed64's integers, or float32's floats added one after another. (Outside the anonymous
// namespace: a coroutine's frame holds it.)
struct HashCacheSegmentSums {
  std::array<std::uint64_t, 3> fixed{};
  std::array<float, 3> light{};
  std::uint64_t count = 0;
};

namespace {

constexpr std::uint64_t kNoOrder = ~std::uint64_t(0);

// A buffer holding `words` (an allocation's storage is only reused, never read).
std::uint32_t Upload32(simt::DeviceMemory& memory, const char* name, const std::vector<std::uint32_t>& words) {
  const std::uint32_t buffer = memory.Allocate32(name, words.size());
  std::copy(words.begin(), words.end(), memory.Words32(buffer).begin());
  return buffer;
}
std::uint32_t Upload64(simt::DeviceMemory& memory, const char* name, const std::vector<std::uint64_t>& words) {
  const std::uint32_t buffer = memory.Allocate64(name, words.size());
  std::copy(words.begin(), words.end(), memory.Words64(buffer).begin());
  return buffer;
}

}  // namespace

simt::KernelTask HashCacheSampleKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args) {
  const std::uint32_t i = ctx.Thread();
  if (i >= args.samples.size()) {
    co_await ctx.Store(args.in.key, i, shared::kCuckooEmpty);
    co_return;
  }
  const HashCacheSample& s = args.samples[i];
  const glm::ivec3 cell = shared::PointCell(args.grid, s.position);
  if (cell.x < 0) {
    co_await ctx.AtomicAdd(args.missed, 0, 1);
    co_await ctx.Store(args.in.key, i, shared::kCuckooEmpty);
    co_return;
  }
  co_await ctx.Store(args.in.key, i, shared::CuckooKey(cell.x, cell.y, cell.z, args.cells_log2));
  co_await ctx.Store(args.in.side, i, shared::FrontWord(s.normal));
  co_await ctx.Store(args.in.origin, i, i);
  for (std::uint32_t c = 0; c < 3; ++c) {
    const float light = shared::Flush(s.light[c]);
    const std::uint64_t word =
        args.fixed64 ? shared::ToFixedPoint(light, args.scale) : std::bit_cast<std::uint32_t>(light);
    co_await ctx.Store(args.in.sums, 3 * std::uint64_t(i) + c, word);
  }
  co_await ctx.Store(args.in.count, i, 1);
}

simt::KernelTask HashCacheLocateKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args) {
  const std::uint32_t i = ctx.Thread();
  co_await ctx.Store(args.perm, i, i);
  const auto key = i < args.element_count ? std::uint32_t(co_await ctx.Load(args.in.key, i)) : shared::kCuckooEmpty;
  if (key == shared::kCuckooEmpty) {
    co_await ctx.Store(args.order, i, kNoOrder);
    co_return;
  }
  std::uint32_t slot = shared::kCuckooEmpty;
  for (std::uint32_t f = 0; f < args.params.functions && slot == shared::kCuckooEmpty; ++f) {
    const std::uint32_t candidate = shared::CuckooSlot(args.params, f, key);
    if (std::uint32_t(co_await ctx.Load(args.map, candidate)) == key) slot = candidate;
  }
  if (slot == shared::kCuckooEmpty) {
    co_await ctx.AtomicAdd(args.level == 0 ? args.missed : args.lost, 0, 1);
    co_await ctx.Store(args.order, i, kNoOrder);
    co_return;
  }
  const auto side = std::uint32_t(co_await ctx.Load(args.in.side, i));
  std::uint32_t front;
  if (args.defect == HashCacheUpdateDefect::kPlainStoreClaim) {
    front = std::uint32_t(co_await ctx.Load(args.front, slot));
    if (front == shared::kFrontUnclaimed) {
      co_await ctx.Store(args.front, slot, side);
      front = side;
    }
  } else {
    const auto old = std::uint32_t(co_await ctx.AtomicCas(args.front, slot, shared::kFrontUnclaimed, side));
    front = old == shared::kFrontUnclaimed ? side : old;
  }
  const bool back = !shared::FacesFront(side, front);
  const auto origin = std::uint32_t(co_await ctx.Load(args.in.origin, i));
  co_await ctx.Store(args.slot, i, slot);
  co_await ctx.Store(args.order, i, (std::uint64_t(shared::SegmentWord(key, back)) << 32) | origin);
}

simt::KernelTask HashCacheSortStepKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args) {
  const std::uint32_t t = ctx.Thread();
  const std::uint32_t j = args.sort_stride;
  const std::uint32_t i = 2 * j * (t / j) + t % j;  // the pair (i, i + j): bit j of i is clear
  const std::uint32_t l = i + j;
  const bool ascending = (i & args.sort_block) == 0;
  const std::uint64_t a = co_await ctx.Load(args.order, i);
  const std::uint64_t b = co_await ctx.Load(args.order, l);
  if (ascending ? a <= b : a >= b) co_return;
  const std::uint64_t pa = co_await ctx.Load(args.perm, i);
  const std::uint64_t pb = co_await ctx.Load(args.perm, l);
  co_await ctx.Store(args.order, i, b);
  co_await ctx.Store(args.order, l, a);
  co_await ctx.Store(args.perm, i, pb);
  co_await ctx.Store(args.perm, l, pa);
}

simt::KernelTask HashCacheReduceKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args) {
  const std::uint32_t i = ctx.Thread();
  const std::uint64_t order = co_await ctx.Load(args.order, i);
  bool head = order != kNoOrder;
  if (head && i > 0) head = (co_await ctx.Load(args.order, i - 1)) >> 32 != order >> 32;
  if (!head) co_return;
  const auto word = std::uint32_t(order >> 32);
  const auto first = std::uint32_t(co_await ctx.Load(args.perm, i));
  const auto slot = std::uint32_t(co_await ctx.Load(args.slot, first));
  HashCacheSegmentSums sums;
  for (std::uint32_t at = i; at < args.positions; ++at) {
    bool past_the_end = false;
    if (at > i) {
      const std::uint64_t next = co_await ctx.Load(args.order, at);
      if (next >> 32 != word) {
        if (args.defect != HashCacheUpdateDefect::kReduceOffByOne || next == kNoOrder) break;
        past_the_end = true;  // the broken boundary: the next segment's first element taken too
      }
    }
    const auto element = std::uint32_t(co_await ctx.Load(args.perm, at));
    for (std::uint32_t c = 0; c < 3; ++c) {
      const std::uint64_t value = co_await ctx.Load(args.in.sums, 3 * std::uint64_t(element) + c);
      const float light = std::bit_cast<float>(std::uint32_t(value));
      sums.fixed[c] += value;
      sums.light[c] = at == i ? light : sums.light[c] + light;
    }
    sums.count += co_await ctx.Load(args.in.count, element);
    if (past_the_end) break;
  }
  // The cell's side, updated once: no other thread touches it in this frame.
  const std::uint64_t side = shared::SegmentBack(word) ? 1 : 0;
  for (std::uint32_t c = 0; c < 3; ++c) {
    const std::uint64_t at = 6 * std::uint64_t(slot) + 3 * side + c;
    const std::uint64_t old = co_await ctx.Load(args.sums, at);
    const std::uint64_t updated =
        args.fixed64 ? old + sums.fixed[c]
                     : std::bit_cast<std::uint32_t>(std::bit_cast<float>(std::uint32_t(old)) + sums.light[c]);
    co_await ctx.Store(args.sums, at, updated);
  }
  const std::uint64_t count = co_await ctx.Load(args.counts, 2 * std::uint64_t(slot) + side);
  co_await ctx.Store(args.counts, 2 * std::uint64_t(slot) + side, count + sums.count);
  if (args.cells_log2 == 0) co_return;
  const auto front = std::uint32_t(co_await ctx.Load(args.front, slot));
  const std::uint64_t at = co_await ctx.AtomicAdd(args.appended, 0, 1);
  co_await ctx.Store(args.out.key, at, shared::ParentKey(shared::SegmentKey(word), args.cells_log2));
  co_await ctx.Store(args.out.side, at, side != 0 ? shared::NegatedFront(front) : front);
  co_await ctx.Store(args.out.origin, at, word);
  for (std::uint32_t c = 0; c < 3; ++c) {
    co_await ctx.Store(args.out.sums, 3 * at + c,
                       args.fixed64 ? sums.fixed[c] : std::bit_cast<std::uint32_t>(sums.light[c]));
  }
  co_await ctx.Store(args.out.count, at, sums.count);
}

simt::KernelTask HashCacheAtomicKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args) {
  const HashCacheSample& s = args.samples[ctx.Thread()];
  const glm::ivec3 finest = shared::PointCell(args.grid, s.position);
  if (finest.x < 0) {
    if (args.level == 0) co_await ctx.AtomicAdd(args.missed, 0, 1);
    co_return;
  }
  const glm::ivec3 cell = finest >> args.level;
  const std::uint32_t key = shared::CuckooKey(cell.x, cell.y, cell.z, args.cells_log2);
  std::uint32_t slot = shared::kCuckooEmpty;
  for (std::uint32_t f = 0; f < args.params.functions && slot == shared::kCuckooEmpty; ++f) {
    const std::uint32_t candidate = shared::CuckooSlot(args.params, f, key);
    if (std::uint32_t(co_await ctx.Load(args.map, candidate)) == key) slot = candidate;
  }
  if (slot == shared::kCuckooEmpty) {
    if (args.level == 0) co_await ctx.AtomicAdd(args.missed, 0, 1);
    co_return;
  }
  const std::uint32_t side = shared::FrontWord(s.normal);
  std::uint32_t front;
  if (args.defect == HashCacheUpdateDefect::kPlainStoreClaim) {
    front = std::uint32_t(co_await ctx.Load(args.front, slot));
    if (front == shared::kFrontUnclaimed) {
      co_await ctx.Store(args.front, slot, side);
      front = side;
    }
  } else {
    const auto old = std::uint32_t(co_await ctx.AtomicCas(args.front, slot, shared::kFrontUnclaimed, side));
    front = old == shared::kFrontUnclaimed ? side : old;
  }
  const std::uint64_t back = shared::FacesFront(side, front) ? 0 : 1;
  for (std::uint32_t c = 0; c < 3; ++c) {
    co_await ctx.AtomicAdd(args.sums, 6 * std::uint64_t(slot) + 3 * back + c,
                           shared::ToFixedPoint(shared::Flush(s.light[c]), args.scale));
  }
  co_await ctx.AtomicAdd(args.counts, 2 * std::uint64_t(slot) + back, 1);
}

EmulatedHashCacheUpdate UpdateHashCacheEmulated(HashCache& cache, std::span<const HashCacheSample> samples,
                                                const EmulatorOptions& options, HashCacheUpdateDefect defect) {
  options.Validate();
  const bool fixed64 = cache.accumulation == Accumulation::kFixed64;
  simt::DeviceMemory memory;
  HashCacheUpdateArgs args;
  args.grid = cache.grid;
  args.fixed64 = fixed64;
  args.scale = SumScale(cache.accumulation, cache.fixed_point_bits);
  args.samples = samples;
  const std::uint32_t span = std::bit_ceil(std::max<std::uint32_t>(2, std::uint32_t(samples.size())));
  args.positions = span;
  args.element_count = std::uint32_t(samples.size());
  args.defect = defect;
  const auto allocate_sums = [&](const char* name, std::size_t count) {
    return fixed64 ? memory.Allocate64(name, count) : memory.Allocate32(name, count);
  };
  std::array<HashCacheElements, 2> elements;
  for (HashCacheElements& e : elements) {
    e.key = memory.Allocate32("element_key", span);
    e.side = memory.Allocate32("element_side", span);
    e.origin = memory.Allocate32("element_origin", span);
    e.sums = allocate_sums("element_sums", 3 * std::size_t(span));
    e.count = memory.Allocate64("element_count", span);
  }
  args.slot = memory.Allocate32("element_slot", span);
  args.order = memory.Allocate64("order", span);
  args.perm = memory.Allocate32("perm", span);
  args.missed = memory.Allocate64("missed", 1);
  args.lost = memory.Allocate64("lost", 1);
  args.appended = memory.Allocate64("appended", 1);

  const auto launch = [&](std::uint32_t threads,
                          simt::KernelTask (*kernel)(simt::ThreadContext&, const HashCacheUpdateArgs&), bool racing) {
    const simt::Kernel bound = [&](simt::ThreadContext& ctx) { return kernel(ctx, args); };
    if (options.mode == simt::Mode::kFast) {
      simt::LaunchFast(memory, threads, bound, options.threads);
      return;
    }
    const std::uint32_t warps = (threads + options.warp_size - 1) / options.warp_size;
    std::unique_ptr<simt::Schedule> parsed;
    simt::Schedule* schedule = racing ? options.schedule_instance : nullptr;
    if (!schedule) {
      // Under an exhaustive search, which drives the finest level's claims, every other launch runs round-robin.
      const std::string policy = options.schedule_instance ? "round-robin" : options.schedule;
      parsed = simt::MakeSchedule(policy, warps, std::uint64_t(warps) * 64);
      schedule = parsed.get();
    }
    simt::LaunchFaithful(memory, threads, options.warp_size, bound, *schedule);
  };

  // Locate and claim, sort, reduce: the elements of the level above are the segments appended.
  const auto sort_and_reduce = [&](std::size_t l) {
    launch(args.positions, HashCacheLocateKernel, l == 0);
    for (args.sort_block = 2; args.sort_block <= args.positions; args.sort_block *= 2) {
      for (args.sort_stride = args.sort_block / 2; args.sort_stride > 0; args.sort_stride /= 2) {
        launch(args.positions / 2, HashCacheSortStepKernel, false);
      }
    }
    memory.Words64(args.appended)[0] = 0;
    launch(args.positions, HashCacheReduceKernel, false);
    args.element_count = std::uint32_t(std::as_const(memory).Words64(args.appended)[0]);
  };
  const bool atomics = cache.update == HashCacheUpdateRule::kAtomics;
  args.in = elements[0];
  args.cells_log2 = cache.grid.resolution_log2;
  if (!atomics) launch(args.positions, HashCacheSampleKernel, false);
  for (std::size_t l = 0; l < cache.levels.size() && (atomics || l == 0 || args.element_count > 0); ++l) {
    HashCacheLevel& level = cache.levels[l];
    args.positions = std::bit_ceil(std::max<std::uint32_t>(2, args.element_count));
    args.in = elements[l % 2];
    args.out = elements[(l + 1) % 2];
    args.level = level.level;
    args.cells_log2 = level.cells_log2;
    args.params = level.map.params;
    args.map = Upload32(memory, "map", level.map.slots);
    args.front = Upload32(memory, "front", level.data.front);
    if (fixed64) {
      args.sums = Upload64(memory, "sums", level.data.fixed_sums);
    } else {
      std::vector<std::uint32_t> bits(level.data.float_sums.size());
      for (std::size_t k = 0; k < bits.size(); ++k) bits[k] = std::bit_cast<std::uint32_t>(level.data.float_sums[k]);
      args.sums = Upload32(memory, "sums", bits);
    }
    args.counts = Upload64(memory, "counts", level.data.counts);
    if (atomics) {
      launch(std::uint32_t(samples.size()), HashCacheAtomicKernel, l == 0);
    } else {
      sort_and_reduce(l);
    }
    level.data.counts = memory.TakeWords64(args.counts);
    if (fixed64) {
      level.data.fixed_sums = memory.TakeWords64(args.sums);
    } else {
      const std::vector<std::uint32_t> bits = memory.TakeWords32(args.sums);
      for (std::size_t k = 0; k < bits.size(); ++k) level.data.float_sums[k] = std::bit_cast<float>(bits[k]);
    }
    level.data.front = memory.TakeWords32(args.front);
  }
  EmulatedHashCacheUpdate result;
  result.missed = std::as_const(memory).Words64(args.missed)[0];
  result.lost = std::as_const(memory).Words64(args.lost)[0];
  return result;
}

}  // namespace hpsf
