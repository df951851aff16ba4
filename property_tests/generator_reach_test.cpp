// The key-identity properties are only as strong as their inputs: these check that the generators really put
// records within a few ulps of the cell and level boundaries they aim at, on both sides, and produce unkeyables.
#include <gtest/gtest.h>

#include "core/key_batch.h"
#include "verifier/generators/record_generators.h"

namespace hpsf::testing {
namespace {

KeyCase LodCase() {
  KeyCase c;
  c.footprint_scale = 0.0123f;
  c.config.jitter_scale = 1.0f;
  return c;
}

TEST(RecordGenerators, CellBoundaryRecordsLandWithinUlpsOfTheBoundaryOnBothSides) {
  for (bool lod : {true, false}) {
    KeyCase c = LodCase();
    c.config.lod = lod;
    c.config.cell_size = 0.37f;
    const shared::KeyParams params = c.Params(0);
    RecordGenerator generator(7);
    int near = 0, below = 0, above = 0;
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
      const KeyPathTrace t = TraceKeyPath(generator.Make(RecordKind::kCellBoundary, params), params);
      bool hit = false;
      for (int axis = 0; axis < 3; ++axis) {
        if (UlpsToInteger(t.quotient[axis]) > 4) continue;
        hit = true;
        below += t.quotient[axis] < std::round(t.quotient[axis]);
        above += t.quotient[axis] > std::round(t.quotient[axis]);
      }
      near += hit;
    }
    EXPECT_GT(near, n * 8 / 10) << "lod " << lod;
    EXPECT_GT(below, n / 5) << "lod " << lod;
    EXPECT_GT(above, n / 5) << "lod " << lod;
  }
}

TEST(RecordGenerators, LevelBoundaryRecordsLandWithinUlpsOfAPowerOfTwo) {
  const KeyCase c = LodCase();
  const shared::KeyParams params = c.Params(0);
  RecordGenerator generator(11);
  int near = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const KeyPathTrace t = TraceKeyPath(generator.Make(RecordKind::kLevelBoundary, params), params);
    near += UlpsToPowerOfTwo(c.footprint_scale * t.path_length) <= 4;
  }
  EXPECT_GT(near, n * 8 / 10);
}

TEST(RecordGenerators, TinyCellSizesProduceUnkeyablesAndDenormalFootprintsTheMinimumLevel) {
  KeyCase c = LodCase();
  c.config.lod = false;
  c.config.cell_size = 1e-30f;
  RecordGenerator generator(3);
  const shared::KeyParams fixed = c.Params(0);
  const auto keys = ComputeKeys(generator.Batch(RecordKind::kUniform, fixed, 100), fixed);
  for (const KeyResult& k : keys) EXPECT_EQ(k.status, shared::kKeyUnkeyable) << ToString(k);

  c.config.lod = true;
  c.footprint_scale = 1e-45f;  // the smallest denormal: w = footprint * d is denormal too
  const shared::KeyParams tiny = c.Params(0);
  for (const KeyResult& k : ComputeKeys(generator.Batch(RecordKind::kUniform, tiny, 100), tiny)) {
    EXPECT_EQ(k.level, -126) << ToString(k);
  }
}

}  // namespace
}  // namespace hpsf::testing
