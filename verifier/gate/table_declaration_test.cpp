// The table declaration (verifier/gate/table_declaration.h): hpsf's own table declared is hpsf's default config; a
// declaration sets exactly what it names; and every bad declaration is an InputError naming the file and the
// place in it, whether the schema, an option's parser or the options taken together reject it.

#include "verifier/gate/table_declaration.h"

#include <string>

#include <gtest/gtest.h>

#include "core/error.h"

namespace hpsf {
namespace {

TEST(TableDeclaration, HpsfsOwnTableDeclaredIsTheDefaultConfig) {
  FilterConfig declared;
  declared.capacity = 64;  // overwritten: the declaration names the capacity
  const std::vector<DeclaredSetting> made = ApplyTableDeclaration(HPSF_TABLES_DIR "/hpsf.json", declared);
  EXPECT_EQ(declared.ToString(), FilterConfig{}.ToString());
  EXPECT_EQ(made.size(), 11u);  // every setting a declaration has
}

TEST(TableDeclaration, SetsWhatItNamesAndKeepsTheRest) {
  FilterConfig config;
  config.seed = 77;
  config.lod = false;
  ApplyTableDeclaration(HPSF_TABLES_DIR "/sharc-buckets.json", config);
  EXPECT_EQ(config.probing, ProbeKind::kBucket);
  EXPECT_EQ(config.probe_limit, 16u);
  EXPECT_EQ(config.capacity, 1u << 22);
  EXPECT_EQ(config.eviction.ToString(), "stale:8");
  EXPECT_EQ(config.compaction, Compaction::kOccupiedList);
  EXPECT_EQ(config.key_identity, KeyIdentity::kFull);
  EXPECT_EQ(config.accumulation, Accumulation::kPackedDecimal);
  EXPECT_EQ(config.seed, 77u);
  EXPECT_FALSE(config.lod);
  FilterConfig small;
  const auto made = ApplyTableDeclarationText(R"({"hpsf_table": 1, "probing": "bucket-window:8"})", "t.json", small);
  ASSERT_EQ(made.size(), 1u);
  EXPECT_EQ(made[0].pointer, "/probing");
  EXPECT_EQ(made[0].option, "--probing");
  EXPECT_EQ(small.probing, ProbeKind::kBucketWindow);
  EXPECT_EQ(small.probe_limit, 8u);
  EXPECT_EQ(small.capacity, FilterConfig{}.capacity);
}

// Each bad declaration: the message starts with the file and names the place.
TEST(TableDeclaration, EveryBadDeclarationNamesTheFileAndThePlace) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"hpsf_table": 1,)", "t.json: not valid JSON at byte"},
      {R"({"hpsf_table": 1, "capacity": 1E+400})", "t.json: not valid JSON: "},  // found by fuzz_declaration
      {R"([1, 2])", "t.json: /hpsf_table: expected 1"},
      {R"({"hpsf_table": 2})", "t.json: /hpsf_table: expected 1"},
      {R"({"hpsf_table": 1, "probe_limit": 4})", "t.json: "},
      {R"({"hpsf_table": 1, "probing": "cuckoo:2"})", "t.json: /probing"},
      {R"({"hpsf_table": 1, "probing": "bucket"})", "t.json: /probing"},
      {R"({"hpsf_table": 1, "probing": "bucket:12"})", "t.json: /probing: bucket:B aligns"},
      {R"({"hpsf_table": 1, "probing": "linear:9999999999"})", "t.json: /probing: the size"},
      {R"({"hpsf_table": 1, "capacity": 1000})", "t.json: /capacity: must be a power of two"},
      {R"({"hpsf_table": 1, "capacity": 64, "probing": "bucket-window:128"})", "t.json: /probing: must lie in [1"},
      {R"({"hpsf_table": 1, "key": {"identity": "hash"}})", "t.json: /key/identity"},
      {R"({"hpsf_table": 1, "key": {"identity": "full", "fingerprint_bits": 32}})", "t.json: /key"},
      {R"({"hpsf_table": 1, "key": {"fingerprint_bits": 40}})", "t.json: /key/fingerprint_bits"},
      {R"({"hpsf_table": 1, "sums": {"encoding": "packed"}})", "t.json: /sums/encoding"},
      {R"({"hpsf_table": 1, "sums": {"fixed_point_bits": 300}})", "t.json: /sums/fixed_point_bits"},
      {R"({"hpsf_table": 1, "passes": {"eviction": "sometimes"}})", "t.json: /passes/eviction: expected"},
      {R"({"hpsf_table": 1, "passes": {"eviction": "priority"}})", "t.json: /passes/eviction: priority reserves"},
      {R"({"hpsf_table": 1, "passes": {"temporal": "ema:2"}})", "t.json: /passes/temporal"},
      {R"({"hpsf_table": 1, "passes": {"level_change": "seed:x"}})", "t.json: /passes/level_change"},
  };
  for (const auto& [text, expected] : cases) {
    FilterConfig config;
    try {
      ApplyTableDeclarationText(text, "t.json", config);
      ADD_FAILURE() << "accepted " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << text << "\n  " << e.what();
    }
  }
  FilterConfig config;
  EXPECT_THROW(ApplyTableDeclaration("/nonexistent/t.json", config), InputError);
}

}  // namespace
}  // namespace hpsf
