// What fuzz_table and fuzz_checker decode their input into: a small table configuration and a batch built to
// collide. Keys are chosen by cell, as property_tests/broken_kernels_test.cpp and grid_batch.h choose them
// (level of detail off, unit cells, no jitter), so a few distinct cells share slot0 in a table of 1 to 256
// slots, windows wrap, and constructed cells share a fingerprint, slot0 or land on the last slot. Sums are fixed64,
// float32 or, for fuzz_table and fuzz_read_back, packed-decimal. Rejected
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
#include "verifier/contract/crosscheck.h"

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

// Whether a packed-decimal verdict fails at level 2 on a word beyond the layout: a sum past 32 bits ("wrapped"), or a
// blend past the words (verifier/checker/table_checker.cpp). Such an input is beyond packed-decimal's range, not a
// bug: the targets classify it rather than report it (a slot's wrap shows whichever cells landed there, aliases
// included, so the reference's cells cannot say in advance which verdicts must name one).
inline bool BeyondPackedDecimal(const FilterConfig& config, const CrosscheckReport& report) {
  if (config.accumulation != Accumulation::kPackedDecimal) return false;
  for (const LevelVerdict& v : report.levels) {
    for (const std::string& failure : v.failures) {
      if (v.level == 2 && (failure.find("wrapped") != std::string::npos ||
                           failure.find("does not fit packed-decimal") != std::string::npos)) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace hpsf

#endif  // HPSF_TOOLS_FUZZ_FUZZ_BATCH_H
