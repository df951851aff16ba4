// The accumulate pass of docs/design/algorithm.md, as an emulator kernel: one thread per record, at each of its
// --levels in turn (core/shared/levels.h); bounded
// linear probing from slot0; a slot whose tag equals the fingerprint is joined, an empty one is claimed with a
// compare-and-swap; each channel is added atomically, then the count; the record's slot is stored. No slot
// within the probe limit is a probe failure. fixed64 adds also report wrap (new < old). With eviction, the slot's
// last-seen frame is stored after the adds (every writer stores the same frame). A tombstone (core/hash_table.h)
// is a slot like any other: its tag is joined or passed, never claimed by another fingerprint; priority eviction's
// tombstones (kTombstoneTag, with claim_tombstones) are claimed: the cell is looked for first, then claimed.
#ifndef HPSF_EMULATED_ACCUMULATE_KERNEL_H
#define HPSF_EMULATED_ACCUMULATE_KERNEL_H

#include <cstdint>
#include <span>

#include "core/filter_config.h"
#include "core/key_batch.h"
#include "core/record.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

struct TableBuffers {
  std::uint32_t tags;        // 32-bit
  std::uint32_t sums;        // three channels per slot, interleaved (slot * 3 + channel), so one slot's sums
                             // share a cache line: 64-bit (fixed64), 32-bit float bits (float32) or 32-bit
                             // integers at 1000 (packed-decimal)
  std::uint32_t counts;      // 64-bit; packed-decimal: 32-bit, the count word (core/shared/packed_sums.h)
  std::uint32_t placements;  // 32-bit, one per record and level, level-major (core/shared/levels.h)
  std::uint32_t wraps;       // 64-bit, two words: fixed64 adds whose sum wrapped, adds whose count wrapped
  std::uint32_t last_seen;   // 32-bit per slot, with eviction only: the last frame a record was added
  // With --second-moments (core/shared/second_moment.h): per slot, the sum of squared brightness, 64-bit (fixed64,
  // at 2^G) or 32-bit float bits (float32).
  bool keeps_squares = false;
  std::uint32_t squares = 0;
};

struct TemporalArgs;         // emulated/temporal_kernel.h
struct EvictionArgs;         // emulated/eviction_kernels.h
struct TransportInPassArgs;  // emulated/broken_transport.h
struct SurvivalInPassArgs;   // emulated/broken_survival.h

struct AccumulateArgs {
  std::span<const Record> records;
  std::span<const KeyResult> keys;         // from core, per record: its own cell's
  KeyParams key_params{};                  // for the keys of coarser levels (core/shared/levels.h)
  std::uint32_t levels = 1;                // --levels
  std::span<const std::uint8_t> accepted;  // CheckRecordInputs passed
  std::uint32_t capacity = 0;
  std::uint32_t probe_limit = 0;
  ProbeKind probing = ProbeKind::kLinear;
  std::uint32_t fingerprint_bits = 32;  // the keys' fingerprints are reduced already; broken kernels reduce their own
  Accumulation accumulation = Accumulation::kFixed64;
  float fixed_point_scale = 1.0f;  // 2^F, or 1000 for packed-decimal (SumScale)
  double square_scale = 1.0;       // 2^G, with --second-moments and fixed64
  bool track_last_seen = false;    // with eviction: store `frame` into buffers.last_seen of every slot added to
  std::uint32_t frame = 0;
  bool claim_tombstones = false;  // with priority eviction (core/shared/table_params.h)
  TableBuffers buffers{};
  // With a blending --temporal and a table before the frame: the temporal pass's arguments. The correct kernel
  // never reads them (the blend is a pass of its own, after this one); D10's variant blends inside this pass.
  const TemporalArgs* temporal = nullptr;
  shared::ProbeScheme scheme() const { return MakeProbeScheme(probing, capacity, probe_limit); }
  // With eviction: the eviction pass's arguments. The correct kernel never reads them (eviction is a pass of its
  // own, after this one); the variant that evicts while records are inserted does.
  const EvictionArgs* eviction = nullptr;
  // Several filtered bounces' reads-current-table variant: the transport's arguments. The correct kernel never reads
  // them (the transport runs before this pass, from the table before the frame).
  const TransportInPassArgs* transport = nullptr;
  // The variant that decides path survival inside this pass (emulated/broken_survival.h). The correct kernel never
  // reads it (the tracer decides before the frame's passes, from the table before the frame).
  const SurvivalInPassArgs* survival = nullptr;
};

// Whether an integer add of `add` to a sum word that held `old` wrapped: at 64 bits, or packed-decimal's 32.
inline bool SumAddWrapped(Accumulation accumulation, std::uint64_t old, std::uint64_t add) {
  if (accumulation == Accumulation::kPackedDecimal) return ((old + add) & 0xFFFFFFFFu) < old;
  return old + add < old;
}
// Whether the add of 1 to a count that held `old` wrapped: a 64-bit count at 2^64 - 1, packed-decimal's 24 bits
// at 2^24 - 1 (the carry lands in the frame counter).
inline bool CountAddWrapped(Accumulation accumulation, std::uint64_t old) {
  if (accumulation == Accumulation::kPackedDecimal) return (old & 0x00FFFFFFu) == 0x00FFFFFFu;
  return old == ~std::uint64_t(0);
}

simt::KernelTask AccumulateKernel(simt::ThreadContext& ctx, const AccumulateArgs& args);

// The key of record's cell `level` levels above its own: KeyOfLevel derives it from the record's own key
// (core/shared/levels.h); a broken variant keys it otherwise (emulated/defect_injection.h).
using LevelKeyFn = KeyResult (*)(const AccumulateArgs& args, std::uint32_t record, std::uint32_t level);
KeyResult KeyOfLevel(const AccumulateArgs& args, std::uint32_t record, std::uint32_t level);
// AccumulateKernel with the coarser levels keyed by `key_of_level`.
simt::KernelTask AccumulateLevels(simt::ThreadContext& ctx, const AccumulateArgs& args, LevelKeyFn key_of_level);

// Fast mode's prefetch for the accumulate's thread i (simt::ThreadPrefetch): the tag, sums and count of its key's
// first slot, where most records end.
void PrefetchAccumulate(const simt::DeviceMemory& memory, const AccumulateArgs& args, std::uint32_t i);

}  // namespace hpsf

#endif  // HPSF_EMULATED_ACCUMULATE_KERNEL_H
