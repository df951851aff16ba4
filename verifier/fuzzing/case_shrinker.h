// Shrinks a failing adversarial case to a small one that still fails, so a repro bundle shows the defect in a
// few records: a sequence's frames dropped one at a time, then delta debugging (Zeller and Hildebrandt 2002, ddmin)
// over each frame's records, then greedy simplifications of the configuration (no eviction and integrating unless
// kept, the automatic F, full fingerprints, fixed64 unless kept, the round-robin schedule, warp 8, the shortest probe
// limit), then the frames and records once more. The result is 1-minimal in each frame's records: removing any one of
// them makes the case pass. "Fails" is whatever the caller's predicate says, typically "the cross-check contract does
// not hold".
#ifndef HPSF_VERIFIER_FUZZING_CASE_SHRINKER_H
#define HPSF_VERIFIER_FUZZING_CASE_SHRINKER_H

#include <cstdint>
#include <functional>

#include "verifier/fuzzing/adversarial_case.h"

namespace hpsf {

using CaseFailsFn = std::function<bool(const AdversarialCase&)>;

struct ShrinkResult {
  AdversarialCase shrunk;
  std::uint64_t checks = 0;  // calls of the predicate
  bool exhausted = false;    // stopped at max_checks: smaller, but maybe not 1-minimal
};

// What was the user's choice and is not simplified: a shader may handle one accumulation mode or one probing
// scheme only, and a team's eviction, temporal, compaction or transport shader runs only while the case evicts,
// blends, compacts or transports (simplified away, the case would shrink into some other failure, or none of the
// shader's).
struct ShrinkKeeps {
  bool accumulation = false;
  bool key_identity = false;  // a shader that reads 64-bit tags only keeps its full keys
  bool probing = false;
  bool eviction = false;
  bool temporal = false;
  bool compaction = false;
  bool transport = false;  // a team's transport shader runs only while the case transports
};

ShrinkResult ShrinkCase(const AdversarialCase& failing, const CaseFailsFn& fails, ShrinkKeeps keep = {},
                        std::uint64_t max_checks = 4000);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_FUZZING_CASE_SHRINKER_H
