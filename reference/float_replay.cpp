#include "reference/float_replay.h"

namespace hpsf {

float ReplayFloatSum(std::span<const Record> records, std::span<const std::uint32_t> order, int channel) {
  float sum = 0.0f;
  for (std::uint32_t record : order) sum += records[record].contribution[channel];
  return sum;
}

}  // namespace hpsf
