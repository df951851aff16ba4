// A team's test of its own hash table with hpsf's verifier: it computes keys with hpsf's key path (compiled here,
// with this project's flags), inserts the records into a table of its own by linear probing, and asks hpsf's
// table checker whether the table is one a correct insertion could have produced. Then it plants a lost update
// and expects the checker to name it. Given a path, it also writes its correct table as a capture through the
// header-only writer (core/capture_writer.h), as an engine would for `hpsf judge`, and reads it back with hpsf's
// reader. Exit 0 when all of that holds.
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/capture_file.h"
#include "core/capture_writer.h"
#include "core/filter_config.h"
#include "core/hash_table.h"
#include "core/key_batch.h"
#include "core/shared/fixed_point.h"
#include "verifier/checker/table_checker.h"
#include "verifier/generators/record_generators.h"

namespace {

// The team's insertion: linear probing from slot0 over probe_limit slots, claim an empty slot, add on a match.
void Insert(const std::vector<hpsf::Record>& records, const std::vector<hpsf::KeyResult>& keys,
            hpsf::HashTableDump& table, std::vector<std::uint32_t>& placements) {
  const float scale = hpsf::shared::PowerOfTwo(table.fixed_point_bits);
  placements.assign(records.size(), hpsf::kNotPlaced);
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (keys[i].status != hpsf::shared::kKeyed) continue;
    placements[i] = hpsf::kProbeFailure;
    for (std::uint32_t probe = 0; probe < table.probe_limit; ++probe) {
      const std::uint32_t slot = (keys[i].slot0 + probe) & (table.capacity - 1);
      if (table.tags[slot] == hpsf::kEmptyTag) table.tags[slot] = keys[i].fingerprint;
      if (table.tags[slot] != keys[i].fingerprint) continue;
      for (int c = 0; c < 3; ++c) {
        table.fixed_sums[slot][c] += hpsf::shared::ToFixedPoint(records[i].contribution[c], scale);
      }
      ++table.counts[slot];
      placements[i] = slot;
      break;
    }
  }
}

// The team's table as a capture of its own keys (six opaque words per record), then read back by hpsf.
bool CaptureRoundTrips(const char* path, const std::vector<hpsf::Record>& records,
                       const std::vector<hpsf::KeyResult>& keys, const hpsf::HashTableDump& table,
                       const std::vector<std::uint32_t>& placements) {
  std::vector<float> contributions;
  std::vector<std::uint32_t> words, home, identities, statuses;
  for (std::size_t i = 0; i < records.size(); ++i) {
    for (int c = 0; c < 3; ++c) contributions.push_back(records[i].contribution[c]);
    const hpsf::KeyResult& k = keys[i];
    for (std::uint32_t w :
         {k.words.cell_x, k.words.cell_y, k.words.cell_z, k.words.level, k.words.normal, k.words.extra}) {
      words.push_back(w);
    }
    home.push_back(k.slot0);
    identities.push_back(k.fingerprint);
    statuses.push_back(k.status);
  }
  hpsf::capture::FrameCapture c;
  c.declaration = R"({"hpsf_table": 1, "capacity": 4096, "probing": "linear:16",
    "sums": {"encoding": "fixed64", "fixed_point_bits": 16}})";
  c.capacity = table.capacity;
  c.fixed_point_bits = table.fixed_point_bits;
  c.key_words = 6;
  c.contributions = contributions;
  c.keys = words;
  c.home_slots = home;
  c.identities = identities;
  c.statuses = statuses;
  c.placements = placements;
  const std::vector<std::uint32_t> tags(table.tags.begin(), table.tags.end());  // fingerprints: 32-bit tags
  c.after = {tags, {reinterpret_cast<const std::uint64_t*>(table.fixed_sums.data()), 3 * table.fixed_sums.size()},
             {},   table.counts,
             {},   {},
             {},   {}};
  if (const std::string error = hpsf::capture::WriteCapture(path, c); !error.empty()) {
    std::printf("capture: %s\n", error.c_str());
    return false;
  }
  const hpsf::Capture read = hpsf::ReadCapture(path);
  const bool same = read.keys == words && read.placements == placements && read.after.tags == table.tags &&
                    read.after.counts == table.counts && read.after.fixed_sums == table.fixed_sums;
  std::printf("capture: %s, %s\n", path, same ? "read back as written" : "read back DIFFERENT");
  return same;
}

}  // namespace

int main(int argc, char** argv) {
  hpsf::FilterConfig config;
  config.capacity = 1u << 12;
  const std::uint32_t count = 3000;
  const hpsf::shared::KeyParams params = hpsf::MakeKeyParams(config, 0.01f, count);

  // Records within ulps of cell and level boundaries, where a contracted multiply-add would move a key.
  hpsf::testing::RecordGenerator generator(20261126);
  std::vector<hpsf::Record> records = generator.Batch(hpsf::testing::RecordKind::kCellBoundary, params, count / 2);
  for (const hpsf::Record& r : generator.Batch(hpsf::testing::RecordKind::kLevelBoundary, params, count / 2)) {
    records.push_back(r);
  }
  for (std::size_t i = 0; i < records.size(); ++i) records[i].contribution = glm::vec4(0.25f, 0.5f, float(i % 7), 0.0f);

  // 1. The key path compiled in this project equals the one compiled into hpsf::core, word for word.
  const std::vector<hpsf::KeyResult> keys = hpsf::ComputeKeys(records, params);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const hpsf::KeyResult here = hpsf::shared::ComputeKey(params, records[i]);
    if (std::memcmp(&here, &keys[i], sizeof here) != 0) ++differing;
  }
  std::printf("keys: %zu of %zu differ from hpsf::core's\n", differing, records.size());

  // 2. The team's table passes the checker.
  hpsf::HashTableDump table;
  table.capacity = config.capacity;
  table.probe_limit = config.probe_limit;
  table.fingerprint_bits = config.fingerprint_bits;
  table.fixed_point_bits = 16;
  table.tags.assign(table.capacity, hpsf::kEmptyTag);
  table.fixed_sums.assign(table.capacity, {0, 0, 0});
  table.counts.assign(table.capacity, 0);
  std::vector<std::uint32_t> placements;
  Insert(records, keys, table, placements);
  const auto clean = hpsf::CheckTable({table, records, keys, placements});
  std::printf("correct table: %zu violations\n", clean.size());
  for (const hpsf::TableViolation& v : clean) std::printf("  %s\n", v.ToString().c_str());

  // 3. The correct table, captured for `hpsf judge`.
  const bool captured = argc < 2 || CaptureRoundTrips(argv[1], records, keys, table, placements);

  // 4. A lost update (one record's add dropped, its placement kept) is named.
  std::size_t victim = 0;
  while (placements[victim] >= table.capacity) ++victim;
  --table.counts[placements[victim]];
  const auto broken = hpsf::CheckTable({table, records, keys, placements});
  const bool named = !broken.empty() && broken.front().invariant == hpsf::TableInvariant::kCountMismatch;
  std::printf("lost update: %zu violations, first: %s\n", broken.size(),
              broken.empty() ? "none" : broken.front().ToString().c_str());

  return differing == 0 && clean.empty() && named && captured ? 0 : 1;
}
