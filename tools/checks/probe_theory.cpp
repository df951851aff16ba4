#include "tools/checks/probe_theory.h"

#include <stdexcept>
#include <vector>

namespace hpsf {
namespace {

// Q_r(M, N) = sum over k >= 0 of binomial(r + k, k) N (N - 1) ... (N - k + 1) / M^k, for r = 0 and 1.
double Q(int r, std::uint64_t slots, std::uint64_t keys) {
  double sum = 0.0, falling = 1.0;  // N^(k falling) / M^k
  for (std::uint64_t k = 0; k <= keys; ++k) {
    const double term = (r == 0 ? 1.0 : double(k + 1)) * falling;
    sum += term;
    if (term < sum * 1e-17) break;
    falling *= double(keys - k) / double(slots);
  }
  return sum;
}

}  // namespace

double ExpectedProbesOnHit(std::uint64_t slots, std::uint64_t keys) {
  if (keys == 0 || keys >= slots) throw std::invalid_argument("ExpectedProbesOnHit: needs 0 < keys < slots");
  return 0.5 * (1.0 + Q(0, slots, keys - 1));
}

double ExpectedProbesOnMiss(std::uint64_t slots, std::uint64_t keys) {
  if (keys >= slots) throw std::invalid_argument("ExpectedProbesOnMiss: needs keys < slots");
  return 0.5 * (1.0 + Q(1, slots, keys));
}

double MeasuredProbesOnHit(std::span<const std::uint32_t> slot0s, std::uint32_t capacity) {
  if (slot0s.empty() || slot0s.size() >= capacity) throw std::invalid_argument("MeasuredProbesOnHit: needs 0 < keys < capacity");
  std::vector<bool> taken(capacity, false);
  std::uint64_t probes = 0;
  for (const std::uint32_t slot0 : slot0s) {
    std::uint32_t slot = slot0 & (capacity - 1u);
    for (++probes; taken[slot]; ++probes) slot = (slot + 1) & (capacity - 1u);
    taken[slot] = true;
  }
  return double(probes) / double(slot0s.size());
}

}  // namespace hpsf
