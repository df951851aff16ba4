// What a hashed backend reads back from a device is untrusted input: a team's shader (--accumulate-spv,
// --eviction-spv) may leave any word in any binding, and a GPU may misbehave. Before the host uses a word as an
// index or a size, it is checked here; a bad word becomes a named failure (which record or slot, what was read,
// what was expected), never undefined behaviour. Words that are only values (tags, sums, counts, last-seen frames
// within range) are left to the table checker and the contract, which judge them with their invariants.
#ifndef HPSF_CORE_READ_BACK_CHECK_H
#define HPSF_CORE_READ_BACK_CHECK_H

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/hashed_run.h"

namespace hpsf {

// A run whose read-back failed ReadBackFaults: the shader's output is itself the defect, and there is no table
// to judge. The contract reports it as a failure of its level 2 (tables); the command line exits 2.
// The key results it carries are values only, so level 1 of the contract still compares them with core's.
class ShaderOutputError : public std::runtime_error {
 public:
  ShaderOutputError(const std::string& shader, std::vector<std::string> faults, std::vector<KeyResult> keys = {});
  const std::vector<std::string>& faults() const { return faults_; }
  const std::vector<KeyResult>& keys() const { return keys_; }

 private:
  std::vector<std::string> faults_;
  std::vector<KeyResult> keys_;
};

// At most `limit` faults of a run's words as read back, in record then slot order:
// - a record's key status is none of kKeyed, kKeyNoVertex, kKeyUnkeyable; a keyed record's slot0 is not below
//   the capacity;
// - a placement is neither a slot below the capacity nor kProbeFailure nor kNotPlaced, or a slot outside its
//   record's candidates (core/shared/probe_scheme.h);
// - with last-seen frames tracked, a slot last seen after this frame;
// - a counter of the stats words larger than the run can produce: fixed64 wraps above 3 per placed record, count
//   wraps above one per placed record, evictions or seeds above the capacity.
// The table's shape (capacity, probe limit, scheme) and the array sizes are the host's own, not read back.
std::vector<std::string> ReadBackFaults(const HashedRun& run, std::uint32_t frame, std::size_t limit = 20);

// The host's work on a run read back from a device: ReadBackFaults (throws ShaderOutputError naming `shader`),
// then the probe statistics (CountProbes) and, with last-seen frames tracked, the tombstones.
void FinishReadBack(HashedRun& run, std::uint32_t frame, const std::string& shader);

}  // namespace hpsf

#endif  // HPSF_CORE_READ_BACK_CHECK_H
