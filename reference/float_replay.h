// The reference's half of the float32 contract: given the order in which the emulator applied a slot's float
// adds, the same adds in the same order in plain C++ (round to nearest) must give the emulator's bits exactly.
#ifndef HPSF_REFERENCE_FLOAT_REPLAY_H
#define HPSF_REFERENCE_FLOAT_REPLAY_H

#include <cstdint>
#include <span>

#include "core/record.h"

namespace hpsf {

float ReplayFloatSum(std::span<const Record> records, std::span<const std::uint32_t> order, int channel);

}  // namespace hpsf

#endif  // HPSF_REFERENCE_FLOAT_REPLAY_H
