#include "verifier/theory/alias_theory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/hash_table.h"

namespace hpsf {

double FingerprintProbability(std::uint32_t tag, std::uint32_t bits) {
  const double share = std::ldexp(1.0, -int(bits));
  if (tag == 1u) return 2.0 * share;
  return tag == kEmptyTag || (bits < 32 && tag >> bits != 0u) ? 0.0 : share;
}

AliasTally InsertAndCountAliases(std::span<const KeyResult> keys, std::uint32_t capacity, std::uint32_t probe_limit,
                                 std::uint32_t fingerprint_bits, ProbeKind probing) {
  if (capacity == 0 || (capacity & (capacity - 1u)) != 0 || probe_limit == 0 || probe_limit > capacity) {
    throw std::invalid_argument("InsertAndCountAliases: needs a power-of-two capacity and 0 < probe_limit <= capacity");
  }
  if (probing == ProbeKind::kBucket && (probe_limit & (probe_limit - 1u)) != 0) {
    throw std::invalid_argument("InsertAndCountAliases: buckets need a power-of-two size");
  }
  const shared::ProbeScheme scheme = MakeProbeScheme(probing, capacity, probe_limit);
  std::vector<std::uint32_t> tags(capacity, kEmptyTag);
  std::vector<std::uint32_t> met;  // the distinct tags a key compares, before seeing its own fingerprint
  AliasTally tally;
  for (const KeyResult& key : keys) {
    if (key.status != shared::kKeyed) continue;
    ++tally.keys;
    met.clear();
    std::uint32_t empty = capacity;  // the first empty slot of the window, if any
    for (std::uint32_t probe = 0; probe < probe_limit; ++probe) {
      const std::uint32_t slot = shared::CandidateSlot(scheme, key.slot0, probe);
      if (tags[slot] == kEmptyTag) {
        empty = slot;
        break;
      }
      met.push_back(tags[slot]);
    }
    tally.compared += double(met.size());
    std::sort(met.begin(), met.end());
    met.erase(std::unique(met.begin(), met.end()), met.end());
    double p = 0.0;
    for (const std::uint32_t tag : met) p += FingerprintProbability(tag, fingerprint_bits);
    tally.predicted += p;
    tally.variance += p * (1.0 - p);
    // Every tag met belongs to another key, since the keys are distinct: a match is an alias.
    if (std::binary_search(met.begin(), met.end(), key.fingerprint)) {
      ++tally.aliased;
    } else if (empty == capacity) {
      ++tally.failed;
    } else {
      tags[empty] = key.fingerprint;
    }
  }
  return tally;
}

}  // namespace hpsf
