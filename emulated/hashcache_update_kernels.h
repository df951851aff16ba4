// The HashCache's frame update by sort and reduce (core/hashcache_update.h holds the reference's) as emulator
// launches, level by level from the finest: locate and claim, one thread per element, each claiming its cell's front
// by compare-and-swap; a bitonic sort of the elements' order words, one launch per step; reduce, one thread per sorted
// position, where the head of each segment adds its segment one element after another, updates its cell's side with a
// plain load and store (no other thread touches that side in the frame) and appends its parent's element at the place
// an atomic counter hands out (the level above sorts its elements, so their places change no sum). Only the claims
// race (and with them, which element reaches a parent first); given the claims, every bit is the reference's under
// every schedule.
#ifndef HPSF_EMULATED_HASHCACHE_UPDATE_KERNELS_H
#define HPSF_EMULATED_HASHCACHE_UPDATE_KERNELS_H

#include <cstdint>
#include <span>

#include "core/hashcache.h"
#include "emulated/emulated_filter.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

// Broken updates the checker must catch.
enum class HashCacheUpdateDefect {
  kNone,
  kPlainStoreClaim,  // the front claimed by a load and a store: two elements may each claim, and judge by their own
  kReduceOffByOne,   // a segment's reduce takes the next segment's first element too
};

// An element buffer set: one entry per element position.
struct HashCacheElements {
  std::uint32_t key = 0;     // 32-bit: the cell, kCuckooEmpty for no element
  std::uint32_t side = 0;    // 32-bit: a front word
  std::uint32_t origin = 0;  // 32-bit
  std::uint32_t sums = 0;    // three per element: fixed64's 64-bit sums, or float32's bits in 32-bit words
  std::uint32_t count = 0;   // 64-bit
};

struct HashCacheUpdateArgs {
  shared::OccupancyGrid grid{};
  bool fixed64 = true;
  float scale = 1.0f;  // 2^F
  std::span<const HashCacheSample> samples;
  std::uint32_t positions = 0;      // the level's sort span: its element count rounded up to a power of two
  std::uint32_t element_count = 0;  // the level's elements (at the finest, the samples)
  // The level.
  shared::CuckooParams params{};
  int level = 0;
  int cells_log2 = 0;
  std::uint32_t map = 0;     // 32-bit: the map's slots
  std::uint32_t front = 0;   // 32-bit
  std::uint32_t sums = 0;    // six per slot, as the elements'
  std::uint32_t counts = 0;  // 64-bit, two per slot
  // The elements of this level, and those its reduce writes for the level above.
  HashCacheElements in, out;
  std::uint32_t slot = 0;      // 32-bit per element: its cell's slot
  std::uint32_t order = 0;     // 64-bit per position: segment word << 32 | origin, all ones for none
  std::uint32_t perm = 0;      // 32-bit per position: the element the sorted position holds
  std::uint32_t missed = 0;    // 64-bit, one word: samples whose cell is not in the finest map
  std::uint32_t lost = 0;      // 64-bit, one word: elements above the finest whose cell is not in the map
  std::uint32_t appended = 0;  // 64-bit, one word: the parents' elements this level's reduce appended
  std::uint32_t sort_block = 0, sort_stride = 0;  // the bitonic step: k and j
  HashCacheUpdateDefect defect = HashCacheUpdateDefect::kNone;
};

simt::KernelTask HashCacheSampleKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args);    // per position
simt::KernelTask HashCacheLocateKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args);    // per position
simt::KernelTask HashCacheSortStepKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args);  // per pair
simt::KernelTask HashCacheReduceKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args);    // per position
// The atomics rule (core/hashcache.h): each sample locates its cell at the level, claims its front and adds its light
// to its side by atomic adds. One launch per level.
simt::KernelTask HashCacheAtomicKernel(simt::ThreadContext& ctx, const HashCacheUpdateArgs& args);  // per sample

struct EmulatedHashCacheUpdate {
  std::uint64_t missed = 0;
  std::uint64_t lost = 0;
};

// `cache` updated by `samples` on the emulator in `options`' mode. Faithful mode runs every launch under the
// options' schedule; an exhaustive one drives the finest level's locate launch alone (where the claims race: the
// orders of every level's would multiply), the rest running round-robin.
EmulatedHashCacheUpdate UpdateHashCacheEmulated(HashCache& cache, std::span<const HashCacheSample> samples,
                                                const EmulatorOptions& options,
                                                HashCacheUpdateDefect defect = HashCacheUpdateDefect::kNone);

}  // namespace hpsf

#endif  // HPSF_EMULATED_HASHCACHE_UPDATE_KERNELS_H
