#include "core/shared/packed_key.h"

#include <gtest/gtest.h>

#include "core/filter_config.h"
#include "core/key_batch.h"
#include "core/record.h"

namespace hpsf {
namespace {

KeyResult RoundTrip(const KeyResult& k, shared::uint key_identity = shared::kIdentityFingerprint) {
  return shared::UnpackKey(shared::PackedKeyCell(k), shared::PackedKeyHashes(k), key_identity);
}

TEST(PackedKey, RoundTripsEveryLevelAndStatus) {
  for (shared::uint status : {shared::kKeyed, shared::kKeyNoVertex, shared::kKeyUnkeyable}) {
    for (int level = -127; level <= 128; ++level) {  // every unbiased exponent of a float
      KeyResult k = shared::EmptyKeyResult(status);
      k.words.cell_x = 0x80000000u;
      k.words.cell_y = 0xFFFFFFFFu;
      k.words.cell_z = 7u;
      k.words.level = shared::uint(level + int(shared::kLevelWordBias));
      k.words.normal = 0xFFFF0001u;
      k.slot0 = 0x12345u;
      k.fingerprint = 0xFFFFFFFFu;
      k.level = level;
      ASSERT_EQ(KeyResultWords(RoundTrip(k)), KeyResultWords(k)) << ToString(k);
    }
  }
}

TEST(PackedKey, RoundTripsComputedKeysOfEveryStatus) {
  VertexSample v;
  v.pixel = 3;
  v.position = glm::vec3(-1.25f, 2.5f, 1e3f);
  v.normal = glm::vec3(0.0f, -1.0f, 0.0f);
  v.previous = glm::vec3(0.0f, 0.0f, -10.0f);
  const std::vector<Record> records = {MakeVertexRecord(v), MakeRecordWithoutVertex(1, 0, glm::vec3(1.0f))};
  FilterConfig fine;  // level of detail on: a keyed record with a negative level
  FilterConfig unkeyable;
  unkeyable.lod = false;
  unkeyable.cell_size = 1e-30f;  // q far beyond 2^31
  FilterConfig full = fine;      // a full key's high word is restored from the words
  full.key_identity = KeyIdentity::kFull;
  int seen[3] = {0, 0, 0};
  bool negative_level = false;
  for (const FilterConfig& config : {fine, unkeyable, full}) {
    const KeyParams params = MakeKeyParams(config, 1e-4f, 2);
    for (const KeyResult& k : ComputeKeys(records, params)) {
      EXPECT_EQ(KeyResultWords(RoundTrip(k, params.key_identity)), KeyResultWords(k)) << ToString(k);
      ++seen[k.status];
      negative_level |= k.status == shared::kKeyed && k.level < 0;
    }
  }
  EXPECT_TRUE(seen[shared::kKeyed] && seen[shared::kKeyNoVertex] && seen[shared::kKeyUnkeyable] && negative_level);
}

}  // namespace
}  // namespace hpsf
