// The schedules the tests of a race explore: the faithful emulator under random and PCT (depth 3) schedules of seeds
// 1 to 20, warps of 4, and fast mode's serial order (one worker thread), 41 in all; and every order of a launch's
// operations, enumerated.
#ifndef HPSF_PROPERTY_TESTS_RACING_SCHEDULES_H
#define HPSF_PROPERTY_TESTS_RACING_SCHEDULES_H

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "emulated/emulated_filter.h"
#include "emulated/simt/schedule.h"

namespace hpsf::testing {

inline std::vector<EmulatorOptions> RacingSchedules() {
  std::vector<EmulatorOptions> schedules;
  for (int seed = 1; seed <= 20; ++seed) {
    for (const std::string& policy : {"random:" + std::to_string(seed), "pct:" + std::to_string(seed) + ":3"}) {
      EmulatorOptions faithful;
      faithful.mode = simt::Mode::kFaithful;
      faithful.warp_size = 4;
      faithful.schedule = policy;
      schedules.push_back(faithful);
    }
  }
  EmulatorOptions serial;
  serial.threads = 1;
  schedules.push_back(serial);
  return schedules;
}

struct Exploration {
  std::uint64_t schedules = 0, caught = 0;
};

// Runs `caught(options)` once per order of the accumulate launch's operations (warps of one lane, the exhaustive
// schedule in `options`) and counts the orders it reports caught.
inline Exploration ExploreEveryOrder(EmulatorOptions options,
                                     const std::function<bool(const EmulatorOptions&)>& caught) {
  simt::ExhaustiveSchedule schedule;
  options.mode = simt::Mode::kFaithful;
  options.warp_size = 1;
  options.schedule_instance = &schedule;
  Exploration e;
  do {
    ++e.schedules;  // every schedule runs: the search learns the next one from this run's decisions
    e.caught += caught(options);
  } while (schedule.Advance());
  return e;
}

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_RACING_SCHEDULES_H
