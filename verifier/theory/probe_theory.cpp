#include "verifier/theory/probe_theory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <boost/math/distributions/binomial.hpp>

namespace hpsf {
namespace {

std::vector<bool> InsertWithoutLimit(std::span<const std::uint32_t> slot0s, std::uint32_t capacity,
                                     std::vector<std::uint32_t>* probes = nullptr) {
  if (slot0s.empty() || slot0s.size() >= capacity)
    throw std::invalid_argument("probe theory: needs 0 < keys < capacity");
  std::vector<bool> taken(capacity, false);
  for (const std::uint32_t slot0 : slot0s) {
    std::uint32_t slot = slot0 & (capacity - 1u);
    for (std::uint64_t probe = 1;; ++probe) {
      if (!taken[slot]) {
        if (probes != nullptr) probes->push_back(std::uint32_t(probe));
        break;
      }
      slot = (slot + 1) & (capacity - 1u);
    }
    taken[slot] = true;
  }
  return taken;
}

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
  double total = 0.0;
  for (const std::uint32_t probes : ProbesOnHit(slot0s, capacity)) total += probes;
  return total / double(slot0s.size());
}

std::vector<std::uint32_t> ProbesOnHit(std::span<const std::uint32_t> slot0s, std::uint32_t capacity) {
  std::vector<std::uint32_t> probes;
  probes.reserve(slot0s.size());
  InsertWithoutLimit(slot0s, capacity, &probes);
  return probes;
}

double ProbabilityWindowFull(std::uint64_t slots, std::uint64_t keys, std::uint64_t window) {
  if (keys >= slots || window == 0 || window >= slots) {
    throw std::invalid_argument("ProbabilityWindowFull: needs keys < slots and 0 < window < slots");
  }
  const double m = double(slots), n = double(keys);
  double p = 0.0;
  for (std::uint64_t length = window; length <= keys; ++length) {
    const double l = double(length);
    const double placements = double(length - window + 1);  // positions of the cluster that cover the window
    double log_ways = std::lgamma(n + 1) - std::lgamma(l + 1) - std::lgamma(n - l + 1) + (l - 1) * std::log(l + 1);
    if (length + 1 < slots) {
      if (keys + 1 == slots) continue;  // one empty slot: the only cluster holds every key
      log_ways += std::log(m - n - 1) + (n - l - 1) * std::log(m - l - 1);
    }
    const double term = placements * std::exp(log_ways - n * std::log(m));
    p += term;
    if (term < 1e-17 * p) break;  // the cluster lengths' tail decays geometrically: the rest cannot count
  }
  return p;
}

double MeasuredWindowFullShare(std::span<const std::uint32_t> slot0s, std::uint32_t capacity, std::uint32_t window) {
  const std::vector<bool> taken = InsertWithoutLimit(slot0s, capacity);
  std::uint64_t full = 0;
  std::uint32_t run = 0;  // taken slots ending at the current one, counted over two turns for the wrap
  for (std::uint64_t i = 0; i < 2ull * capacity; ++i) {
    run = taken[i & (capacity - 1u)] ? run + 1 : 0;
    if (i >= capacity && run >= window) ++full;  // the window that ends here, starting window - 1 slots back
  }
  return double(full) / double(capacity);
}

double ExpectedBucketOverflowShare(std::uint64_t slots, std::uint64_t keys, std::uint64_t bucket) {
  if (keys == 0 || bucket == 0 || bucket > slots || slots % bucket != 0) {
    throw std::invalid_argument("ExpectedBucketOverflowShare: needs keys > 0 and buckets that tile the table");
  }
  // E[max(0, X - B)] = E[X] - B + E[max(0, B - X)]: a sum over x < B only, so exact for any N.
  const boost::math::binomial_distribution<> per_bucket(double(keys), double(bucket) / double(slots));
  double short_of_full = 0.0;
  for (std::uint64_t x = 0; x < bucket && x <= keys; ++x) {
    short_of_full += double(bucket - x) * boost::math::pdf(per_bucket, double(x));
  }
  const double overflow = double(keys) * double(bucket) / double(slots) - double(bucket) + short_of_full;
  return std::max(0.0, overflow) * double(slots / bucket) / double(keys);
}

}  // namespace hpsf
