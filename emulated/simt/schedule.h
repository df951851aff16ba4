// Who runs next on the emulated GPU. At each warp step the schedule picks one ready warp, and it orders every
// group of conflicting operations of that step (same address, at least one write); all other interleavings
// are equivalent and not explored. Policies: round-robin, seeded random, PCT (Burckhardt et al. 2010) and
// exhaustive enumeration for tiny launches. All randomness comes from the counter RNG.
#ifndef HPSF_EMULATED_SIMT_SCHEDULE_H
#define HPSF_EMULATED_SIMT_SCHEDULE_H

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace hpsf::simt {

class Schedule {
 public:
  virtual ~Schedule() = default;
  // Returns an index into `ready` (the warps that have a pending operation, ascending).
  virtual std::size_t PickWarp(std::span<const std::uint32_t> ready) = 0;
  // Puts one group of conflicting operations (lane indices, ascending) into the order they are applied.
  virtual void OrderConflict(std::span<std::uint32_t> lanes) = 0;
  virtual std::string Name() const = 0;
};

class RoundRobinSchedule : public Schedule {
 public:
  std::size_t PickWarp(std::span<const std::uint32_t> ready) override;
  void OrderConflict(std::span<std::uint32_t>) override {}  // lane order
  std::string Name() const override { return "round-robin"; }

 private:
  std::int64_t last_ = -1;
};

class RandomSchedule : public Schedule {
 public:
  explicit RandomSchedule(std::uint32_t seed) : seed_(seed) {}
  std::size_t PickWarp(std::span<const std::uint32_t> ready) override;
  void OrderConflict(std::span<std::uint32_t> lanes) override;
  std::string Name() const override { return "random:" + std::to_string(seed_); }

 protected:
  std::uint32_t Next(std::uint32_t bound);  // uniform in [0, bound)

 private:
  std::uint32_t seed_;
  std::uint32_t draws_ = 0;
};

// Probabilistic concurrency testing: warps get random distinct priorities; the highest-priority ready warp
// runs; at depth - 1 random change points (among the first `expected_steps` steps) the running warp drops to
// the lowest priorities. Finds a bug of depth d with probability at least 1 / (n k^(d-1)).
class PctSchedule : public RandomSchedule {
 public:
  PctSchedule(std::uint32_t seed, std::uint32_t depth, std::uint32_t warps, std::uint64_t expected_steps);
  std::size_t PickWarp(std::span<const std::uint32_t> ready) override;
  std::string Name() const override { return name_; }

 private:
  std::vector<std::int64_t> priority_;
  std::vector<std::uint64_t> change_points_;
  std::uint64_t step_ = 0;
  std::string name_;
};

// Replays a prefix of decisions, then takes the first option at every new decision and records how many
// there were; Advance() moves to the next unexplored schedule, depth first.
class ExhaustiveSchedule : public Schedule {
 public:
  std::size_t PickWarp(std::span<const std::uint32_t> ready) override;
  void OrderConflict(std::span<std::uint32_t> lanes) override;
  std::string Name() const override { return "exhaustive"; }
  // Prepares the next schedule; false when every schedule has been explored.
  bool Advance();

 private:
  std::uint64_t Decide(std::uint64_t options);
  struct Decision {
    std::uint64_t choice;
    std::uint64_t options;
  };
  std::vector<Decision> decisions_;
  std::size_t position_ = 0;
};

// Parses round-robin | random:SEED | pct:SEED:DEPTH | exhaustive (a ConfigError naming --schedule otherwise).
std::unique_ptr<Schedule> MakeSchedule(const std::string& text, std::uint32_t warps, std::uint64_t expected_steps);

}  // namespace hpsf::simt

#endif  // HPSF_EMULATED_SIMT_SCHEDULE_H
