// Wall time for the commands' reports: seconds on the steady clock since a point. No output bit depends on it.
#ifndef HPSF_TOOLS_HPSF_SECONDS_SINCE_H
#define HPSF_TOOLS_HPSF_SECONDS_SINCE_H

#include <chrono>

namespace hpsf {

inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_SECONDS_SINCE_H
