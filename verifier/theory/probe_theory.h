// Linear probing's theory (Knuth, TAOCP vol. 3, section 6.4, Algorithm L), exact for a circular table of M
// slots holding N keys under uniform hashing, and the same figures measured from a table's slot0s. The
// statistics tests and `hpsf stats` hold the index hash to it: a hash that clusters, or one too regular for its
// keys, moves the mean probe count away from the theory.
#ifndef HPSF_VERIFIER_THEORY_PROBE_THEORY_H
#define HPSF_VERIFIER_THEORY_PROBE_THEORY_H

#include <cstdint>
#include <span>
#include <vector>

namespace hpsf {

// Expected probes of a successful search, 1/2 (1 + Q0(M, N - 1)), about 1/2 (1 + 1 / (1 - a)) at load a = N / M.
double ExpectedProbesOnHit(std::uint64_t slots, std::uint64_t keys);
// Expected probes of an unsuccessful search (the insertion of key N + 1), 1/2 (1 + Q1(M, N)), about
// 1/2 (1 + 1 / (1 - a)^2).
double ExpectedProbesOnMiss(std::uint64_t slots, std::uint64_t keys);

// The mean probes of a successful search over the keys whose first slots are `slot0s`, inserted by linear
// probing without a limit into a table of `capacity` slots (a power of two, more than the keys). The total
// displacement, hence the mean, does not depend on the order of insertion.
double MeasuredProbesOnHit(std::span<const std::uint32_t> slot0s, std::uint32_t capacity);
// The same keys' probes one by one, in their order.
std::vector<std::uint32_t> ProbesOnHit(std::span<const std::uint32_t> slot0s, std::uint32_t capacity);

// The probability that a new key exceeds a probe limit of `window` slots: that the `window` slots from its
// slot0 are all taken, in a table of M slots holding N keys under uniform hashing. Exact: a sum over the length
// L >= window of the cluster that covers the window (L keys parked in L slots, (L + 1)^(L - 1) ways; the other
// N - L keys in the remaining M - L slots leaving both neighbours empty, (M - N - 1)(M - L - 1)^(N - L - 1) ways).
double ProbabilityWindowFull(std::uint64_t slots, std::uint64_t keys, std::uint64_t window);

// The share of the table's `capacity` windows of `window` slots that are full after the keys whose first slots
// are `slot0s` were inserted by linear probing without a limit: the measured ProbabilityWindowFull.
double MeasuredWindowFullShare(std::span<const std::uint32_t> slot0s, std::uint32_t capacity, std::uint32_t window);

// Aligned buckets (bucket:B): the expected share of N keys that find their bucket of B slots full, in a table of M
// slots under uniform hashing. A bucket's keys are Binomial(N, B / M), and every key past the B-th of its bucket
// fails, so the share is (M / B) E[max(0, X - B)] / N, exact by linearity whatever the order of insertion.
double ExpectedBucketOverflowShare(std::uint64_t slots, std::uint64_t keys, std::uint64_t bucket);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_THEORY_PROBE_THEORY_H
