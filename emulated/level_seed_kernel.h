// The seed pass of resolution changes (core/level_seed.h) as an emulator kernel, one thread per record and level (a
// touch, core/shared/levels.h: thread t is record t mod n at t / n levels above its own cell), after the
// accumulate and before the temporal blend: a record placed in a slot that held no samples before the frame
// claims the slot's seeding with a compare-and-swap on a per-slot flag (0 to 1), so one record per slot seeds it;
// it computes its cell's seed from the table before the frame (read on the host side: that table is not written
// during the pass) and adds it with atomics, then marks the flag 2. Every record of a cell computes the same seed,
// so which one wins does not matter unless two cells alias in the slot (the contract classifies those).
#ifndef HPSF_EMULATED_LEVEL_SEED_KERNEL_H
#define HPSF_EMULATED_LEVEL_SEED_KERNEL_H

#include <cstdint>
#include <span>

#include "core/hash_table.h"
#include "core/key_batch.h"
#include "core/level_seed.h"
#include "emulated/accumulate_kernel.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

struct LevelSeedArgs {
  std::span<const KeyResult> keys;
  std::uint32_t capacity = 0;
  bool fixed = true;
  bool normal_in_index = true;
  LevelSeed level_seed;
  const HashTableDump* previous = nullptr;  // the table before the frame
  TableBuffers buffers{};
  std::uint32_t seeded = 0;        // 32-bit per slot: 0, 1 claimed, 2 seeded
  std::uint32_t seeded_count = 0;  // 64-bit, one word: slots seeded
};

simt::KernelTask LevelSeedKernel(simt::ThreadContext& ctx, const LevelSeedArgs& args);

}  // namespace hpsf

#endif  // HPSF_EMULATED_LEVEL_SEED_KERNEL_H
