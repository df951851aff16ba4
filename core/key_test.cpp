#include "core/shared/key.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/filter_config.h"
#include "core/key_batch.h"
#include "core/record.h"

namespace hpsf {
namespace {

using shared::CellOf;
using shared::KeyWords;

TEST(Cell, FloorNotTruncationForNegativeCoordinates) {
  const shared::Cell c = CellOf(glm::vec3(-0.5f, -1.0f, -1.5f), 1.0f);
  ASSERT_TRUE(c.keyable);
  EXPECT_EQ(c.index, glm::ivec3(-1, -1, -2));
  EXPECT_EQ(CellOf(glm::vec3(-1e-30f, 0.5f, 1.0f), 1.0f).index, glm::ivec3(-1, 0, 1));
  EXPECT_EQ(CellOf(glm::vec3(-0.0f, 0.0f, std::nextafter(-3.0f, 0.0f)), 1.0f).index, glm::ivec3(0, 0, -3));
  EXPECT_EQ(CellOf(glm::vec3(-3.0f, 5.0f, -4.5f), 0.5f).index, glm::ivec3(-2, 2, -3));
}

TEST(Cell, DenormalQuotientsAreFlushedToTheZeroCell) {
  // x * 2^-l below the normal range is flushed on every device, so the cell is 0 even for a negative x.
  const shared::Cell c = CellOf(glm::vec3(-1e-30f, 1e-30f, 0.0f), std::ldexp(1.0f, -30));
  ASSERT_TRUE(c.keyable);
  EXPECT_EQ(c.index, glm::ivec3(0, 0, 0));
}

TEST(Cell, UnkeyableFromTwoToThe31) {
  const float limit = 2147483648.0f;
  EXPECT_FALSE(CellOf(glm::vec3(limit, 0.0f, 0.0f), 1.0f).keyable);
  EXPECT_FALSE(CellOf(glm::vec3(0.0f, -limit, 0.0f), 1.0f).keyable);
  EXPECT_FALSE(CellOf(glm::vec3(0.0f, 0.0f, std::numeric_limits<float>::infinity()), 1.0f).keyable);
  EXPECT_FALSE(CellOf(glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f), 1.0f).keyable);
  const shared::Cell below = CellOf(glm::vec3(std::nextafter(limit, 0.0f), -std::nextafter(limit, 0.0f), 0.0f), 1.0f);
  ASSERT_TRUE(below.keyable);
  EXPECT_EQ(below.index, glm::ivec3(2147483520, -2147483520, 0));
}

TEST(Fingerprint, ZeroReducesToOneAtEveryWidth) {
  for (shared::uint bits = 8; bits <= 32; ++bits) {
    EXPECT_EQ(shared::ReduceFingerprint(0u, bits), 1u) << bits;
    const shared::uint top_bits_zero = bits == 32 ? 0u : (0xFFFFFFFFu >> bits);
    EXPECT_EQ(shared::ReduceFingerprint(top_bits_zero, bits), 1u) << bits;
    EXPECT_EQ(shared::ReduceFingerprint(0xFFFFFFFFu, bits), bits == 32 ? 0xFFFFFFFFu : (1u << bits) - 1u) << bits;
  }
}

TEST(Fingerprint, ConstructedKeysWhoseFingerprintReducesToZeroGetOne) {
  // Search cells until the top 8 bits of the full fingerprint are 0: the case D3 is about.
  int found = 0;
  for (shared::uint x = 0; x < 100000 && found < 3; ++x) {
    KeyWords k{x, 7u, 0xFFFFFFF0u, 130u, 5u, 0u};
    if ((shared::FullFingerprint(k) >> 24) != 0u) continue;
    ++found;
    EXPECT_EQ(shared::Fingerprint(k, 8), 1u);
    for (shared::uint bits = 8; bits <= 32; ++bits) EXPECT_NE(shared::Fingerprint(k, bits), 0u);
  }
  EXPECT_EQ(found, 3) << "the search must reach keys with a zero 8-bit fingerprint";
}

TEST(IndexHash, NormalBucketOnlyInTheFingerprintWhenAskedTo) {
  KeyWords a{1u, 2u, 3u, 128u, 0u, 0u}, b = a;
  b.normal = 5u;
  EXPECT_EQ(shared::IndexHash(a, 0u), shared::IndexHash(b, 0u));
  EXPECT_NE(shared::IndexHash(a, 1u), shared::IndexHash(b, 1u));
  EXPECT_NE(shared::FullFingerprint(a), shared::FullFingerprint(b));
}

TEST(NormalBucket, SignOctantSeesNegativeZero) {
  EXPECT_EQ(shared::SignOctant(glm::vec3(0.0f, 0.0f, 1.0f)), 0u);
  EXPECT_EQ(shared::SignOctant(glm::vec3(-0.0f, 0.0f, 1.0f)), 1u);
  EXPECT_EQ(shared::SignOctant(glm::vec3(0.0f, -0.0f, -1.0f)), 6u);
  EXPECT_EQ(shared::OctahedralBucket(0xFFFF0000u, 4), 0xF0u);
  EXPECT_EQ(shared::OctahedralBucket(0x0000FFFFu, 16), 0xFFFFu);
}

VertexSample TestVertex() {
  VertexSample v;
  v.pixel = 17;
  v.sample = 3;
  v.position = glm::vec3(1.25f, 2.5f, -3.75f);
  v.normal = glm::vec3(0.0f, 1.0f, 0.0f);
  v.previous = glm::vec3(1.25f, 2.5f, -13.75f);
  v.d_prefix = 0.0f;
  return v;
}

TEST(ComputeKey, NoVertexAndUnkeyableRecords) {
  FilterConfig config;
  const shared::KeyParams params = MakeKeyParams(config, 0.01f, 1);
  EXPECT_EQ(shared::ComputeKey(params, MakeRecordWithoutVertex(0, 0, glm::vec3(1.0f))).status, shared::kKeyNoVertex);

  config.lod = false;
  config.cell_size = 1e-30f;  // q = x * 1e30 is far beyond 2^31
  const shared::KeyResult k = shared::ComputeKey(MakeKeyParams(config, 0.01f, 1), MakeVertexRecord(TestVertex()));
  EXPECT_EQ(k.status, shared::kKeyUnkeyable) << ToString(k);
}

TEST(ComputeKey, WithoutJitterTheCellIsTheFloorOfThePositionOverTheCellSize) {
  FilterConfig config;
  config.jitter_scale = 0.0f;
  // d = 10, footprint 0.05: w = 0.5 exactly, so the cell size is 2^-1.
  const shared::KeyResult k = shared::ComputeKey(MakeKeyParams(config, 0.05f, 1), MakeVertexRecord(TestVertex()));
  ASSERT_EQ(k.status, shared::kKeyed) << ToString(k);
  EXPECT_EQ(k.level, -1);
  EXPECT_EQ(k.words.level, 127u);
  EXPECT_EQ(glm::ivec3(int(k.words.cell_x), int(k.words.cell_y), int(k.words.cell_z)), glm::ivec3(2, 5, -8));
  EXPECT_EQ(k.words.normal, shared::SignOctant(glm::vec3(0.0f, 1.0f, 0.0f)));
  EXPECT_EQ(k.slot0, shared::IndexHash(k.words, 1u) & (config.capacity - 1u));
  EXPECT_EQ(k.fingerprint, shared::Fingerprint(k.words, 32u));
}

TEST(ComputeKey, TheLevelIsRecomputedAfterTheJitter) {
  // d is just below a power of two before the jitter, so a jitter away from the camera crosses the level
  // boundary; the key must use the level of the jittered position (docs/design/defects.md, D5).
  FilterConfig config;
  config.jitter_scale = 1.0f;
  VertexSample v = TestVertex();
  v.normal = glm::vec3(1.0f, 0.0f, 0.0f);  // tangent plane contains z, the direction to the camera
  v.previous = glm::vec3(1.25f, 2.5f, 0.0f);
  v.position.z = std::nextafter(16.0f, 0.0f);
  const float footprint = 1.0f / 16.0f;  // w just below 1: level -1 before jitter
  int crossed = 0;
  for (shared::uint sample = 0; sample < 64; ++sample) {
    v.sample = sample;
    const Record r = MakeVertexRecord(v);
    const shared::KeyParams params = MakeKeyParams(config, footprint, 1);
    const shared::KeyResult k = shared::ComputeKey(params, r);
    ASSERT_EQ(k.status, shared::kKeyed);
    const int before =
        shared::LevelOfDetail(footprint, shared::PathLength(0.0f, glm::vec3(r.position), glm::vec3(r.previous)),
                              params.level_min, params.level_max);
    EXPECT_EQ(before, -1);
    crossed += k.level != before;
  }
  EXPECT_GT(crossed, 10) << "jitter should push about half of the samples over the level boundary";
}

TEST(ComputeKeys, RunsTheSharedKeyForEveryRecordInOrder) {
  std::vector<Record> records = {MakeVertexRecord(TestVertex()), MakeRecordWithoutVertex(1, 0, glm::vec3(0.0f))};
  const shared::KeyParams params = MakeKeyParams(FilterConfig{}, 0.05f, 2);
  const std::vector<KeyResult> keys = ComputeKeys(records, params);
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(KeyResultWords(keys[0]), KeyResultWords(shared::ComputeKey(params, records[0])));
  EXPECT_EQ(keys[1].status, shared::kKeyNoVertex);
}

}  // namespace
}  // namespace hpsf
