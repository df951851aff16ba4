// The full stored key (--key-identity full, core/shared/full_key.h): hpsf's key words packed into 64 bits, one to
// one within their ranges and never the empty tag or priority's tombstone; a cell beyond the ranges unkeyable; on
// every hashed backend the table stores each cell's whole key, and otherwise the same bits as a table of 32-bit
// fingerprints; where 8-bit fingerprints alias, no two cells share a slot; and a full key matched by its low word
// alone (a 32-bit compare of a 64-bit key) is caught in the emulator and as a shader, and is harmless with
// fingerprints, whose high word is 0.

#include "core/shared/full_key.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend.h"
#include "core/error.h"
#include "core/hash_table.h"
#include "core/key_batch.h"
#include "core/record.h"
#include "core/shared/eviction_priority.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "property_tests/hashed_backends.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "verifier/checker/table_checker.h"
#include "verifier/generators/record_generators.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

using shared::KeyWords;

KeyWords Words(int x, int y, int z, shared::uint level, shared::uint normal) {
  return {shared::uint(x), shared::uint(y), shared::uint(z), level, normal, 0u};
}

// The packing undone, field by field: what the checker would have to trust if the packing lost a bit.
KeyWords Unpack(shared::uvec2 key) {
  const std::uint64_t v = shared::IdentityValue(key);
  const auto cell = [&](int shift) {
    const std::uint32_t bits = std::uint32_t(v >> shift) & 0x1FFFFu;
    return (bits & 0x10000u) ? bits | 0xFFFE0000u : bits;  // sign-extends 17 bits
  };
  return {cell(0), cell(17), cell(34), std::uint32_t(v >> 51) & 0x1FFu, std::uint32_t(v >> 60) & 7u, 0u};
}

bool SameWords(const KeyWords& a, const KeyWords& b) {
  return a.cell_x == b.cell_x && a.cell_y == b.cell_y && a.cell_z == b.cell_z && a.level == b.level &&
         a.normal == b.normal && a.extra == b.extra;
}

TEST(FullKey, PacksEveryWordOneToOneAndNeverTheEmptyOrTombstoneTag) {
  RecordGenerator g(0x5EEDu);
  const int edges[] = {shared::kFullKeyCellMin,     shared::kFullKeyCellMin + 1, -1, 0, 1,
                       shared::kFullKeyCellMax - 1, shared::kFullKeyCellMax};
  std::map<std::uint64_t, KeyWords> words_of;
  for (int round = 0; round < 20000; ++round) {
    const bool edge = round % 2 == 0;
    const auto coordinate = [&] {
      return edge ? edges[g.Bits() % 7u] : g.UniformInt(shared::kFullKeyCellMin, shared::kFullKeyCellMax);
    };
    // Level words 1..256: an unbiased exponent -127..128 plus 128; normal buckets 0..7.
    const KeyWords w = Words(coordinate(), coordinate(), coordinate(), 1u + g.Bits() % 256u, g.Bits() % 8u);
    ASSERT_TRUE(shared::FullKeyFits(w));
    const shared::uvec2 key = shared::FullKey(w);
    ASSERT_TRUE(SameWords(Unpack(key), w)) << std::hex << shared::IdentityValue(key);
    ASSERT_NE(key.y, 0u) << "the high word holds the level word, never 0";
    ASSERT_NE(shared::IdentityValue(key), std::uint64_t(shared::kTombstoneTag));
    ASSERT_EQ(key.y >> 31, 0u) << "bit 63 is unused";
    // Equal keys only for equal words (the edge rounds repeat some).
    const auto [it, inserted] = words_of.try_emplace(shared::IdentityValue(key), w);
    ASSERT_TRUE(inserted || SameWords(it->second, w)) << std::hex << it->first;
  }
  EXPECT_GT(words_of.size(), 15000u);
  // Out of range by one, in each word.
  EXPECT_FALSE(shared::FullKeyFits(Words(shared::kFullKeyCellMax + 1, 0, 0, 128u, 0u)));
  EXPECT_FALSE(shared::FullKeyFits(Words(0, shared::kFullKeyCellMin - 1, 0, 128u, 0u)));
  EXPECT_FALSE(shared::FullKeyFits(Words(0, 0, 1 << 20, 128u, 0u)));
  EXPECT_FALSE(shared::FullKeyFits(Words(0, 0, 0, 512u, 0u)));
  EXPECT_FALSE(shared::FullKeyFits(Words(0, 0, 0, 128u, 8u)));
  KeyWords extra = Words(0, 0, 0, 128u, 0u);
  extra.extra = 1u;
  EXPECT_FALSE(shared::FullKeyFits(extra));
}

VertexSample VertexAt(float x) {
  VertexSample v;
  v.position = glm::vec3(x, 0.5f, 0.5f);
  v.previous = v.position + glm::vec3(0.0f, 0.0f, -10.0f);
  return v;
}

TEST(FullKey, ACellBeyondItsRangeIsUnkeyableAndOneAtItsEdgeIsKeyed) {
  FilterConfig fingerprint;
  fingerprint.lod = false;
  fingerprint.cell_size = 1.0f;
  fingerprint.jitter_scale = 0.0f;
  FilterConfig full = fingerprint;
  full.key_identity = KeyIdentity::kFull;
  const std::vector<Record> records = {MakeVertexRecord(VertexAt(65535.5f)), MakeVertexRecord(VertexAt(65536.5f)),
                                       MakeVertexRecord(VertexAt(-65535.5f)), MakeVertexRecord(VertexAt(-65536.5f))};
  const std::vector<KeyResult> by_fingerprint = ComputeKeys(records, MakeKeyParams(fingerprint, 0.01f, 4));
  const std::vector<KeyResult> by_full = ComputeKeys(records, MakeKeyParams(full, 0.01f, 4));
  for (const KeyResult& k : by_fingerprint) EXPECT_EQ(k.status, shared::kKeyed) << ToString(k);
  EXPECT_EQ(by_full[0].status, shared::kKeyed) << ToString(by_full[0]);
  EXPECT_EQ(by_full[1].status, shared::kKeyUnkeyable) << ToString(by_full[1]);
  EXPECT_EQ(by_full[2].status, shared::kKeyed) << ToString(by_full[2]);  // cell -65536
  EXPECT_EQ(by_full[3].status, shared::kKeyUnkeyable) << ToString(by_full[3]);
  // A keyed record's words, slot0 and level are the fingerprint key's; only the identity differs.
  for (int i : {0, 2}) {
    EXPECT_TRUE(SameWords(by_full[i].words, by_fingerprint[i].words));
    EXPECT_EQ(by_full[i].slot0, by_fingerprint[i].slot0);
    EXPECT_EQ(StoredIdentity(by_full[i]), shared::IdentityValue(shared::FullKey(by_full[i].words)));
    EXPECT_EQ(StoredIdentity(by_fingerprint[i]), by_fingerprint[i].fingerprint);
  }
}

TEST(FullKey, ItsConfigurationIsValidatedAndNamed) {
  EXPECT_EQ(ParseKeyIdentity("fingerprint"), KeyIdentity::kFingerprint);
  EXPECT_EQ(ParseKeyIdentity("full"), KeyIdentity::kFull);
  EXPECT_EQ(ToString(KeyIdentity::kFull), "full");
  const auto error_of = [](const FilterConfig& c) {
    try {
      c.Validate();
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  for (const char* bad : {"", "Full", "full-key", "64"}) {
    try {
      ParseKeyIdentity(bad);
      ADD_FAILURE() << bad << " parsed";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--key-identity: ", 0), 0u) << e.what();
    }
  }
  FilterConfig c;
  c.key_identity = KeyIdentity::kFull;
  EXPECT_EQ(error_of(c), "");
  c.eviction = ParseEviction("priority");  // no full key is the tombstone: 32 bits of config are fine
  EXPECT_EQ(error_of(c), "");
  c.fingerprint_bits = 16;
  EXPECT_EQ(error_of(c).rfind("--fingerprint-bits: a full key", 0), 0u) << error_of(c);
  c.fingerprint_bits = 32;
  c.normal = ParseNormalKey("octahedral:2");
  EXPECT_EQ(error_of(c).rfind("--normal: a full key keeps 3 bits", 0), 0u) << error_of(c);
  c.normal = ParseNormalKey("octahedral:1");
  EXPECT_EQ(error_of(c), "");
}

std::vector<TableViolation> Check(const HashedRun& run, const RecordBatch& batch, const FilterConfig& config) {
  return CheckTable({run.table, batch.records, run.keys, run.placements, nullptr, config.eviction, config.frame,
                     config.temporal, config.level_seed, config.normal_in_index});
}

// Per record: its slot's count and sums, or its placement where it has no slot. Not the slot: which of two cells
// that share a home slot claims it first is the order of atomics, which no run promises.
std::vector<std::vector<std::uint64_t>> CellsOfRecords(const HashedRun& run) {
  std::vector<std::vector<std::uint64_t>> cells;
  for (const std::uint32_t slot : run.placements) {
    if (slot >= run.table.capacity) {
      cells.push_back({slot});
      continue;
    }
    const auto& sums = run.table.fixed_sums[slot];
    cells.push_back({run.table.counts[slot], sums[0], sums[1], sums[2]});
  }
  return cells;
}

TEST(FullKey, EveryHashedBackendStoresEachCellsWholeKeyAndOtherwiseAFingerprintTablesBits) {
  const RecordBatch batch = TracedBatch("cornell", 32, 2);
  FilterConfig fingerprint;
  fingerprint.capacity = 1u << 14;
  FilterConfig full = fingerprint;
  full.key_identity = KeyIdentity::kFull;
  std::vector<HashedBackend> by_full = HashedBackends(), by_fingerprint = HashedBackends();
  for (std::size_t b = 0; b < by_full.size(); ++b) {
    const std::string& name = by_full[b].name;
    const Image& image = by_full[b].backend->FilterFrame(batch, full);
    const Image& expected = by_fingerprint[b].backend->FilterFrame(batch, fingerprint);
    const HashedRun& run = RunOf(*by_full[b].backend);
    ASSERT_EQ(run.table.key_identity, KeyIdentity::kFull) << name;
    std::uint64_t placed = 0;
    for (std::size_t i = 0; i < run.placements.size(); ++i) {
      const std::uint32_t slot = run.placements[i];
      if (slot >= run.table.capacity) continue;
      ++placed;
      ASSERT_EQ(run.table.tags[slot], shared::IdentityValue(shared::FullKey(run.keys[i].words)))
          << name << ", record " << i;
      ASSERT_GE(run.table.tags[slot], std::uint64_t(1) << 32) << name << ": a full key has a high word";
    }
    EXPECT_GT(placed, 1000u) << name;
    const std::vector<TableViolation> violations = Check(run, batch, full);
    EXPECT_TRUE(violations.empty()) << name << ": " << violations.front().ToString();
    // No probe failure and no alias among 32-bit fingerprints here: the two tables differ in their tags alone.
    ASSERT_EQ(run.probe_failures + RunOf(*by_fingerprint[b].backend).probe_failures, 0u) << name;
    EXPECT_EQ(CellsOfRecords(run), CellsOfRecords(RunOf(*by_fingerprint[b].backend))) << name;
    EXPECT_TRUE(image.pixels == expected.pixels) << name;
  }
}

std::size_t CountAliased(const HashedRun& run) {
  const std::vector<bool> aliased = AliasedSlots(run);
  return std::size_t(std::count(aliased.begin(), aliased.end(), true));
}

// A crowded table of 8-bit fingerprints aliases cells; the same table of full keys never does, and every record
// that found a slot is in its own cell's.
TEST(FullKey, NoTwoCellsShareASlotWhereEightBitFingerprintsAlias) {
  const RecordBatch batch = TracedBatch("cornell", 48, 2);
  FilterConfig fingerprint;
  fingerprint.capacity = 1u << 10;
  fingerprint.probe_limit = 32;
  fingerprint.fingerprint_bits = 8;
  FilterConfig full = fingerprint;
  full.fingerprint_bits = 32;
  full.key_identity = KeyIdentity::kFull;
  std::vector<HashedBackend> backends = HashedBackends();
  for (HashedBackend& b : backends) {
    b.backend->FilterFrame(batch, fingerprint);
    const std::uint64_t aliased_by_fingerprint = CountAliased(RunOf(*b.backend));
    b.backend->Reset();  // another table
    b.backend->FilterFrame(batch, full);
    const HashedRun& run = RunOf(*b.backend);
    EXPECT_GT(aliased_by_fingerprint, 10u) << b.name;
    EXPECT_EQ(CountAliased(run), 0u) << b.name;
    const std::vector<TableViolation> violations = Check(run, batch, full);
    EXPECT_TRUE(violations.empty()) << b.name << ": " << violations.front().ToString();
  }
}

// A crowded table of full keys, where cells of one column (the same x and y) share their key's low word.
TEST(FullKey, AFullKeyMatchedByItsLowWordIsCaughtInTheEmulatorAndAsAShader) {
  const RecordBatch batch = TracedBatch("cornell", 32, 2);
  FilterConfig config;
  config.capacity = 256;
  config.key_identity = KeyIdentity::kFull;
  FilterConfig fingerprint = config;
  fingerprint.key_identity = KeyIdentity::kFingerprint;
  EmulatedBackend emulated(EmulatorOptions{}, KernelWithDefect(Defect::kFullKeyLowWord));
  VulkanBackend shader(TestDevice(StagingPolicy::kAuto),
                       std::string(HPSF_SHADER_VARIANT_DIR) + "/accumulate_FULL_KEY_LOW_WORD.spv");
  for (Backend* backend : {static_cast<Backend*>(&emulated), static_cast<Backend*>(&shader)}) {
    backend->FilterFrame(batch, config);
    const std::vector<TableViolation> caught = Check(RunOf(*backend), batch, config);
    ASSERT_FALSE(caught.empty()) << backend->Name();
    EXPECT_EQ(caught.front().invariant, TableInvariant::kTagIsNotTheFingerprint) << caught.front().ToString();
    EXPECT_NE(caught.front().ToString().find(", full key "), std::string::npos) << caught.front().ToString();
    // With fingerprints the high word is 0: the low word is the whole tag, and the same kernel is correct.
    backend->Reset();
    backend->FilterFrame(batch, fingerprint);
    const std::vector<TableViolation> clean = Check(RunOf(*backend), batch, fingerprint);
    EXPECT_TRUE(clean.empty()) << backend->Name() << ": " << clean.front().ToString();
  }
}

}  // namespace
}  // namespace hpsf::testing
