#include "emulated/simt/schedule.h"

#include <algorithm>
#include <charconv>
#include <numeric>

#include "core/error.h"
#include "core/shared/rng.h"

namespace hpsf::simt {

std::size_t RoundRobinSchedule::PickWarp(std::span<const std::uint32_t> ready) {
  // The first ready warp after the last one that ran, cyclically.
  auto next = std::upper_bound(ready.begin(), ready.end(), last_,
                               [](std::int64_t v, std::uint32_t w) { return v < std::int64_t(w); });
  const std::size_t index = next == ready.end() ? 0 : std::size_t(next - ready.begin());
  last_ = ready[index];
  return index;
}

std::uint32_t RandomSchedule::Next(std::uint32_t bound) {
  const std::uint32_t bits = shared::RandomBits(shared::RngCounter{seed_, 0x5C4EDu, draws_++, 0u, 0u}, 0u);
  return static_cast<std::uint32_t>((std::uint64_t(bits) * bound) >> 32);
}

std::size_t RandomSchedule::PickWarp(std::span<const std::uint32_t> ready) { return Next(std::uint32_t(ready.size())); }

void RandomSchedule::OrderConflict(std::span<std::uint32_t> lanes) {
  for (std::size_t i = lanes.size(); i > 1; --i) std::swap(lanes[i - 1], lanes[Next(std::uint32_t(i))]);
}

PctSchedule::PctSchedule(std::uint32_t seed, std::uint32_t depth, std::uint32_t warps, std::uint64_t expected_steps)
    : RandomSchedule(seed), priority_(warps), name_("pct:" + std::to_string(seed) + ":" + std::to_string(depth)) {
  // Initial priorities depth .. depth + warps - 1 in random order; change points take 0 .. depth - 2.
  std::vector<std::uint32_t> order(warps);
  std::iota(order.begin(), order.end(), 0u);
  OrderConflict(order);
  for (std::uint32_t i = 0; i < warps; ++i) priority_[order[i]] = std::int64_t(depth) + i;
  for (std::uint32_t i = 0; i + 1 < depth; ++i)
    change_points_.push_back(1 + Next(std::uint32_t(std::max<std::uint64_t>(expected_steps, 1))));
}

std::size_t PctSchedule::PickWarp(std::span<const std::uint32_t> ready) {
  ++step_;
  auto highest = [&] {
    return std::size_t(std::max_element(ready.begin(), ready.end(),
                                        [&](std::uint32_t a, std::uint32_t b) { return priority_[a] < priority_[b]; }) -
                       ready.begin());
  };
  for (std::size_t i = 0; i < change_points_.size(); ++i) {
    if (change_points_[i] == step_) priority_[ready[highest()]] = std::int64_t(i);
  }
  return highest();
}

std::uint64_t ExhaustiveSchedule::Decide(std::uint64_t options) {
  if (position_ < decisions_.size()) return decisions_[position_++].choice;
  decisions_.push_back({0, options});
  ++position_;
  return 0;
}

std::size_t ExhaustiveSchedule::PickWarp(std::span<const std::uint32_t> ready) { return Decide(ready.size()); }

void ExhaustiveSchedule::OrderConflict(std::span<std::uint32_t> lanes) {
  std::uint64_t permutations = 1;
  for (std::size_t i = 2; i <= lanes.size(); ++i) permutations *= i;
  std::uint64_t code = Decide(permutations);
  // Decode the Lehmer code `code` into a permutation of the lanes.
  std::vector<std::uint32_t> pool(lanes.begin(), lanes.end());
  for (std::size_t i = 0; i < lanes.size(); ++i) {
    std::uint64_t factorial = 1;
    for (std::size_t k = 2; k < pool.size(); ++k) factorial *= k;
    const std::size_t pick = std::size_t(code / factorial);
    code %= factorial;
    lanes[i] = pool[pick];
    pool.erase(pool.begin() + std::ptrdiff_t(pick));
  }
}

bool ExhaustiveSchedule::Advance() {
  decisions_.resize(std::min(decisions_.size(), position_));
  while (!decisions_.empty() && decisions_.back().choice + 1 >= decisions_.back().options) decisions_.pop_back();
  position_ = 0;
  if (decisions_.empty()) return false;
  ++decisions_.back().choice;
  return true;
}

std::unique_ptr<Schedule> MakeSchedule(const std::string& text, std::uint32_t warps, std::uint64_t expected_steps) {
  auto number = [&](std::string_view s) {
    std::uint32_t v = 0;
    auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (error != std::errc() || end != s.data() + s.size() || s.empty()) {
      throw ConfigError("--schedule",
                        "expected round-robin, random:SEED, pct:SEED:DEPTH or exhaustive; got '" + text + "'");
    }
    return v;
  };
  if (text == "round-robin") return std::make_unique<RoundRobinSchedule>();
  if (text == "exhaustive") return std::make_unique<ExhaustiveSchedule>();
  if (text.rfind("random:", 0) == 0) return std::make_unique<RandomSchedule>(number(std::string_view(text).substr(7)));
  if (text.rfind("pct:", 0) == 0) {
    const std::string_view rest = std::string_view(text).substr(4);
    const std::size_t colon = rest.find(':');
    if (colon == std::string_view::npos) number("");
    const std::uint32_t depth = number(rest.substr(colon + 1));
    if (depth == 0) throw ConfigError("--schedule", "PCT depth must be at least 1; got '" + text + "'");
    return std::make_unique<PctSchedule>(number(rest.substr(0, colon)), depth, warps, expected_steps);
  }
  number("");
  return nullptr;
}

}  // namespace hpsf::simt
