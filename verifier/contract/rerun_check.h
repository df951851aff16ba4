// Level 4 of the cross-check (docs/design/contract.md): what a rerun of a hashed backend on the same inputs must
// repeat, and what the order of its atomics may change. A gate that judges order-dependent bits fails on correct
// code, so the promise is classified first and only what it covers is compared.
#ifndef HPSF_VERIFIER_CONTRACT_RERUN_CHECK_H
#define HPSF_VERIFIER_CONTRACT_RERUN_CHECK_H

#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/hashed_run.h"

namespace hpsf {

enum class RerunPromise {
  // A faithful emulator run is a function of (inputs, policy, seed): table, placements and image repeat bit for
  // bit (the caller compares the trace hash too).
  kEverything,
  // Unordered (fast mode on all cores, a device), fixed64, nothing failed or aliased in either run: a record's
  // slot may change with the order of claims, but its count and exact sums do not, nor does the image.
  kCountsSumsAndImage,
  // Unordered, fixed64, nothing failed or aliased, but a neighbourhood search's lookup found another cell in either
  // run (verifier/contract/search_check.h): which slots a lookup crosses follows the order of claims, so the image is
  // not promised; the counts and sums are.
  kCountsAndSums,
  // Unordered, float32, nothing failed or aliased: counts as above; the sums are rounded in the order the adds
  // happened to apply, so their bits and the image's are not promised (level 2 bounds the sums).
  kCounts,
  // Unordered with probe failures or aliases in either run: which records fail or merge depends on the order;
  // nothing beyond level 2.
  kNothing,
};
const char* ToString(RerunPromise promise);

// ordered: the run's order of memory operations is fixed by a schedule (the emulator's faithful mode).
// lookup_aliased: a search's lookup read another cell in either run.
RerunPromise RerunPromiseFor(bool ordered, Accumulation accumulation, bool failed_or_aliased,
                             bool lookup_aliased = false);

// The differences between two runs on the same inputs that the promise rules out, each naming a record or the
// image; empty when the rerun keeps the promise.
std::vector<std::string> CompareReruns(const HashedRun& first, const HashedRun& second, RerunPromise promise);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_RERUN_CHECK_H
