// The schedules the tests of a race explore: the faithful emulator under random and PCT (depth 3) schedules of seeds
// 1 to 20, warps of 4, and fast mode's serial order (one worker thread), 41 in all.
#ifndef HPSF_PROPERTY_TESTS_RACING_SCHEDULES_H
#define HPSF_PROPERTY_TESTS_RACING_SCHEDULES_H

#include <string>
#include <vector>

#include "emulated/emulated_filter.h"

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

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_RACING_SCHEDULES_H
