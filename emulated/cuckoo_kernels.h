// The construction of a HashCache level's cuckoo map (core/cuckoo_map.h holds the reference's) as an emulator launch,
// as Alcantara et al. build theirs on a GPU: one thread per key exchanges it into its first candidate by an atomic
// exchange; a key it evicts it carries on to that key's next candidate, until a slot was empty or the chain passes its
// limit, where it raises the launch's failure flag (the key it holds is out of the map). A failed attempt is rebuilt
// from empty slots with new constants and Roth's growth, as the reference's. Which keys end in which slots depends on
// the schedule; the checker's invariants must hold under every one.
#ifndef HPSF_EMULATED_CUCKOO_KERNELS_H
#define HPSF_EMULATED_CUCKOO_KERNELS_H

#include <cstdint>
#include <span>

#include "core/cuckoo_map.h"
#include "emulated/emulated_filter.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

// Broken constructions the checker must catch.
enum class CuckooInsertDefect {
  kNone,
  kDropAtLimit,    // the chain's limit drops the key held and raises nothing
  kLoadThenStore,  // the exchange as a load and a store: two threads may take the same key out of a slot
};

struct CuckooArgs {
  shared::CuckooParams params{};
  std::span<const std::uint32_t> keys;
  std::uint32_t max_chain = 0;
  std::uint32_t slots = 0;   // 32-bit: the map
  std::uint32_t failed = 0;  // 64-bit, one word: inserts that passed the limit
  CuckooInsertDefect defect = CuckooInsertDefect::kNone;
};

simt::KernelTask CuckooInsertKernel(simt::ThreadContext& ctx, const CuckooArgs& args);  // per key

// The map of `keys` built on the emulator in `options`' mode, attempt after attempt as BuildCuckooMap.
CuckooBuild BuildCuckooMapEmulated(std::span<const std::uint32_t> keys, const CuckooBuildOptions& build,
                                   const EmulatorOptions& options,
                                   CuckooInsertDefect defect = CuckooInsertDefect::kNone);

}  // namespace hpsf

#endif  // HPSF_EMULATED_CUCKOO_KERNELS_H
