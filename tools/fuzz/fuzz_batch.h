// What fuzz_table and fuzz_checker decode their input into: a small table configuration and a batch built to
// collide. Keys are chosen by cell, as property_tests/broken_kernels_test.cpp and grid_batch.h choose them
// (level of detail off, unit cells, no jitter), so a few distinct cells share slot0 in a table of 1 to 256
// slots, windows wrap, and constructed cells share a fingerprint, slot0 or land on the last slot. Sums are fixed64,
// float32 or, for fuzz_table, packed-decimal. Rejected
// (NaN, infinite, negative), unkeyable and vertex-less records are mixed in. Sizes are capped so that one input
// runs in milliseconds.
#ifndef HPSF_TOOLS_FUZZ_FUZZ_BATCH_H
#define HPSF_TOOLS_FUZZ_FUZZ_BATCH_H

#include <cstdint>
#include <string>

#include <fuzzer/FuzzedDataProvider.h>

#include "core/filter_config.h"
#include "core/record.h"
#include "emulated/emulated_filter.h"

namespace hpsf {

inline constexpr std::uint32_t kFuzzMaxRecords = 192;
inline constexpr std::uint32_t kFuzzMaxCapacityLog2 = 8;

struct FuzzCase {
  FilterConfig config;
  EmulatorOptions faithful;  // warp size and schedule from the input
  EmulatorOptions fast;      // two worker threads
  RecordBatch batch;
  std::string ToString() const;  // the configuration and each record's cell and kind, for a failure's message
};

// packed_sums: a quarter of the inputs keep packed-decimal sums (a target that judges them); otherwise those are
// fixed64, so an input decodes to the same case for every target but in its sums' encoding.
FuzzCase DecodeFuzzCase(FuzzedDataProvider& input, bool packed_sums = false);

}  // namespace hpsf

#endif  // HPSF_TOOLS_FUZZ_FUZZ_BATCH_H
