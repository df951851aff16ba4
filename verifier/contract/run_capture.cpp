#include "verifier/contract/run_capture.h"

#include <span>
#include <vector>

#include "core/capture_writer.h"
#include "core/count_words.h"
#include "core/error.h"

namespace hpsf {
namespace {

static_assert(sizeof(std::array<std::uint64_t, 3>) == 24 && sizeof(std::array<float, 3>) == 12);

// The 32-bit words a packed-decimal table holds on a device, kept alive beside its TableBuffers.
struct PackedWords {
  std::vector<std::uint32_t> sums, counts;
};

// A table of full keys as 64-bit tags; a fingerprint table's tags, each below 2^32, narrowed into `tags32`. A
// packed-decimal table's sums and count words (core/shared/packed_sums.h) as the device holds them, into `packed`.
capture::TableBuffers BuffersOf(const HashTableDump& t, std::vector<std::uint32_t>& tags32, PackedWords& packed) {
  capture::TableBuffers b;
  if (t.key_identity == KeyIdentity::kFull) {
    b.full_tags = t.tags;
  } else {
    tags32.assign(t.tags.begin(), t.tags.end());
    b.tags = tags32;
  }
  if (t.accumulation == Accumulation::kPackedDecimal) {
    packed.sums.resize(3 * t.fixed_sums.size());
    packed.counts.resize(t.counts.size());
    for (std::size_t s = 0; s < t.counts.size(); ++s) {
      for (int c = 0; c < 3; ++c) packed.sums[3 * s + std::size_t(c)] = std::uint32_t(t.fixed_sums[s][c]);
    }
    PackCountWords(t.counts, t.frame_counters, packed.counts);
    b.packed_sums = packed.sums;
    b.count_words = packed.counts;
  } else {
    b.fixed_sums = {reinterpret_cast<const std::uint64_t*>(t.fixed_sums.data()), 3 * t.fixed_sums.size()};
    b.float_sums = {reinterpret_cast<const float*>(t.float_sums.data()), 3 * t.float_sums.size()};
    b.counts = t.counts;
  }
  b.last_seen = t.last_seen;
  return b;
}

}  // namespace

void WriteRunCapture(const std::string& path, const std::string& declaration, const RecordBatch& batch,
                     std::uint32_t frame, const HashedRun& run, const HashTableDump* before) {
  const bool full_keys = run.table.key_identity == KeyIdentity::kFull;
  const std::size_t n = batch.records.size();
  std::vector<float> contributions(3 * n);
  std::vector<std::uint32_t> keys(6 * n), home(n), identities(full_keys ? 0 : n), statuses(n);
  std::vector<std::uint64_t> full_identities(full_keys ? n : 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) contributions[3 * i + std::size_t(c)] = batch.records[i].contribution[c];
    const KeyResult& k = run.keys[i];
    const std::uint32_t words[6] = {k.words.cell_x, k.words.cell_y, k.words.cell_z,
                                    k.words.level,  k.words.normal, k.words.extra};
    std::copy(words, words + 6, keys.begin() + std::ptrdiff_t(6 * i));
    home[i] = k.slot0;
    if (full_keys) {
      full_identities[i] = StoredIdentity(k);
    } else {
      identities[i] = k.fingerprint;
    }
    statuses[i] = k.status;
  }
  const capture::RecordView records{batch.width, batch.height, batch.samples_per_pixel, batch.fov_y_radians,
                                    std::as_bytes(std::span<const Record>(batch.records))};
  std::vector<std::uint32_t> tags_before, tags_after;
  PackedWords packed_before, packed_after;
  const capture::TableBuffers table_before =
      before ? BuffersOf(*before, tags_before, packed_before) : capture::TableBuffers{};
  capture::FrameCapture c;
  c.declaration = declaration;
  c.frame = frame;
  c.capacity = run.table.capacity;
  c.fixed_point_bits = run.table.fixed_point_bits;
  c.float32_sums = run.table.accumulation == Accumulation::kFloat32;
  c.packed_sums = run.table.accumulation == Accumulation::kPackedDecimal;
  c.full_keys = full_keys;
  c.key_words = 6;
  c.contributions = contributions;
  c.keys = keys;
  c.home_slots = home;
  c.identities = identities;
  c.full_identities = full_identities;
  c.statuses = statuses;
  c.placements = run.placements;
  c.hpsf_records = &records;
  c.before = before ? &table_before : nullptr;
  c.after = BuffersOf(run.table, tags_after, packed_after);
  const std::span<const std::uint32_t> occupied = run.table.occupied;
  if (run.table.compacted) c.occupied = &occupied;
  const std::span<const std::uint32_t> occupied_before = before ? before->occupied : std::span<const std::uint32_t>();
  if (before && before->compacted && run.table.compacted) c.occupied_before = &occupied_before;
  if (const std::string error = capture::WriteCapture(path, c); !error.empty()) throw InputError(error);
}

}  // namespace hpsf
