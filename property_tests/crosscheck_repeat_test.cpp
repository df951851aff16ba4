// The gate never fails on correct code: the cross-check of every built-in scene with all three
// backends, the emulator in fast mode (where float32 sums follow the threads' timing, as a device's do), passes
// 20 times in a row in float32 and in fixed64. Its verdict must not depend on timing, so no run may fail; that a
// rerun which breaks the promise is caught is shown deterministically in verifier/contract/rerun_check_test.cpp.
#include <gtest/gtest.h>

#include "property_tests/traced_batch.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf::testing {
namespace {

constexpr int kRepeats = 20;

TEST(CrosscheckRepeat, EveryBuiltInScenePassesTwentyTimesWithAllBackendsInBothAccumulations) {
  for (const std::string scene :
       {"cornell", "furnace", "cornell-far-1e5", "cornell-far-1e7", "cornell-tiny", "cornell-zero-red"}) {
    const RecordBatch batch =
        TracedBatch(scene, 64, 2);  // as `hpsf crosscheck SCENE --size 64x64 --spp 2 --capacity 32768`
    for (const Accumulation accumulation : {Accumulation::kFloat32, Accumulation::kFixed64}) {
      FilterConfig config;
      config.capacity =
          1u << 15;  // load at most 1/4: the promises of runs with nothing failed or aliased are exercised
      config.accumulation = accumulation;
      for (int run = 0; run < kRepeats; ++run) {
        const CrosscheckReport report =
            Crosscheck(batch, config, {"reference", "emulated", "vulkan"}, EmulatorOptions{});
        ASSERT_TRUE(report.Passed()) << scene << (accumulation == Accumulation::kFloat32 ? " float32" : " fixed64")
                                     << ", run " << run + 1 << " of " << kRepeats << ": " << report.FirstFailure();
      }
    }
  }
}

}  // namespace
}  // namespace hpsf::testing
