// Lost updates in the emulator's fast mode, through the whole filter: every record of a Cornell batch forced into
// one cell (level of detail off, a cell larger than the box, no jitter, no normal key), so both cores add to the
// same four words 60,000 times a run. Counts, and in fixed64 the sums, must come out exact on every run: the
// table checker compares them with the records placed in each slot. With the add made a load then a store, 5
// of 5 executions of this test failed (each within its 20 runs); emulated/simt/fast_atomics_test.cpp hammers the
// atomics alone, harder.
#include <gtest/gtest.h>

#include "emulated/emulated_filter.h"
#include "property_tests/traced_batch.h"
#include "reference/reference_filter.h"
#include "verifier/checker/table_checker.h"

namespace hpsf::testing {
namespace {

constexpr int kRuns = 20;

TEST(ContendedAtomics, FastModeCountsAndFixedSumsAreExactOnEveryRun) {
  const RecordBatch batch = TracedBatch("cornell", 128, 4);
  FilterConfig config;
  config.lod = false;
  config.cell_size = 4096.0f;  // the box spans about 560 units from the origin: one cell
  config.jitter_scale = 0.0f;
  config.normal.mode = NormalMode::kNone;
  config.capacity = 1u << 10;
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    config.accumulation = accumulation;
    const FilterResult reference = ReferenceFilter(batch, config);
    ASSERT_EQ(reference.cells.size(), 1u);
    ASSERT_GT(reference.stats.records_with_vertex, 50000u);
    for (int run = 0; run < kRuns; ++run) {
      const EmulatedRun emulated = EmulatedFilter(batch, config, EmulatorOptions{});
      const std::vector<TableViolation> violations =
          CheckTable({emulated.table, batch.records, emulated.keys, emulated.placements});
      ASSERT_TRUE(violations.empty()) << (accumulation == Accumulation::kFixed64 ? "fixed64" : "float32") << ", run "
                                      << run + 1 << ": " << violations.front().ToString();
      std::uint64_t counted = 0;
      for (const std::uint64_t count : emulated.table.counts) counted += count;
      ASSERT_EQ(counted, reference.stats.records_with_vertex - reference.stats.unkeyable -
                             reference.stats.rejected_non_finite - reference.stats.rejected_negative);
    }
  }
}

}  // namespace
}  // namespace hpsf::testing
