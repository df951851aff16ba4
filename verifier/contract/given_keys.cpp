#include "verifier/contract/given_keys.h"

#include <array>
#include <map>
#include <set>

#include "core/input_check.h"
#include "core/shared/eviction_priority.h"
#include "core/shared/fixed_point.h"
#include "core/shared/packed_sums.h"

namespace hpsf {
namespace {

using KeyWordsOf = std::array<std::uint32_t, 6>;

KeyWordsOf WordsOf(const KeyResult& k) {
  return {k.words.cell_x, k.words.cell_y, k.words.cell_z, k.words.level, k.words.normal, k.words.extra};
}

std::string RecordName(std::size_t i) { return "record " + std::to_string(i); }

bool Keyed(const KeyResult& k, const Record& r) {
  return k.status == shared::kKeyed && CheckRecordInputs(r) == InputVerdict::kAccepted;
}

struct ExactCell {
  std::uint64_t count = 0;
  std::array<std::uint64_t, 3> fixed_sum = {};
  std::set<std::uint32_t> slots;  // where its records went; kProbeFailure for those that failed
  std::size_t first_record = 0;
};

}  // namespace

std::uint64_t JudgeGivenKeys(std::span<const KeyResult> keys, std::span<const Record> records, std::uint32_t capacity,
                             const FilterConfig& config, const std::string& prefix, LevelVerdict& verdict) {
  const std::uint32_t bits = config.fingerprint_bits;
  std::map<KeyWordsOf, std::size_t> first_of;
  std::uint64_t judged = 0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const KeyResult& k = keys[i];
    const std::string record = prefix + RecordName(i);
    if (k.status > shared::kKeyUnkeyable) {
      verdict.Fail(record + ": status " + std::to_string(k.status) + " is none of keyed, no vertex, unkeyable");
      continue;
    }
    if (!Keyed(k, records[i])) continue;
    ++judged;
    if (k.slot0 >= capacity) {
      verdict.Fail(record + ": home slot " + std::to_string(k.slot0) + " outside the table of " +
                   std::to_string(capacity) + " slots");
    }
    // A fingerprint is at most `bits` wide; a full key is any 64-bit word but 0 (core/key_identity.h).
    const SlotTag identity = StoredIdentity(k);
    const unsigned width = config.key_identity == KeyIdentity::kFull ? 64u : bits;
    if (identity == 0) {
      verdict.Fail(record + ": identity 0, the empty slot's marker: its cell can never be told from an empty slot");
    } else if (width < 64 && (identity >> width) != 0) {
      verdict.Fail(record + ": identity " + std::to_string(identity) + " wider than the declared " +
                   std::to_string(bits) + " bits");
    } else if (config.eviction.by_priority() && identity == shared::kTombstoneTag) {
      verdict.Fail(record + ": identity 0xFFFFFFFF, priority eviction's tombstone marker");
    }
    const auto [first, inserted] = first_of.emplace(WordsOf(k), i);
    if (!inserted) {
      const KeyResult& f = keys[first->second];
      if (f.slot0 != k.slot0 || StoredIdentity(f) != identity) {
        verdict.Fail(record + " and " + RecordName(first->second) + " share their key words but not their " +
                     (f.slot0 != k.slot0 ? "home slot" : "identity") + ": the key is not a function of the cell");
      }
    }
  }
  return judged;
}

std::uint64_t CompareWithExactMap(std::span<const Record> records, const HashedRun& run, const HashTableDump* before,
                                  const std::vector<bool>& classified, const FilterConfig& config,
                                  const std::string& prefix, LevelVerdict& verdict) {
  const HashTableDump& t = run.table;
  const bool fixed = IntegerSums(t.accumulation);
  const bool packed = t.accumulation == Accumulation::kPackedDecimal;
  const float scale = SumScale(t.accumulation, t.fixed_point_bits);
  std::map<KeyWordsOf, ExactCell> cells;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const KeyResult& k = run.keys[i];
    if (!Keyed(k, records[i])) continue;
    ExactCell& cell = cells[WordsOf(k)];
    if (cell.count == 0) cell.first_record = i;
    ++cell.count;
    for (int ch = 0; ch < 3 && fixed; ++ch) {
      cell.fixed_sum[ch] += shared::ToFixedPoint(records[i].contribution[ch], scale);
    }
    cell.slots.insert(run.placements[i]);
  }
  for (const auto& [words, cell] : cells) {
    if (cell.slots.size() > 1) {
      std::string where;
      for (std::uint32_t s : cell.slots) {
        where += (where.empty() ? "" : ", ") + (s == kProbeFailure ? std::string("failed") : std::to_string(s));
      }
      verdict.Fail(prefix + "the cell of " + RecordName(cell.first_record) + " is split: its " +
                   std::to_string(cell.count) + " records went to " + where);
    }
  }
  std::uint64_t compared = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const std::uint32_t slot = run.placements[i];
    if (slot >= t.capacity || classified[slot]) continue;
    const auto found = cells.find(WordsOf(run.keys[i]));
    if (found == cells.end()) continue;  // placed without a key: level 2's
    const ExactCell& cell = found->second;
    const bool history = before && before->counts[slot] != 0;
    if (history && config.temporal.blends()) continue;  // the blend is level 2's
    ++compared;
    const std::string record = prefix + RecordName(i) + " at slot " + std::to_string(slot);
    if (packed) {  // the settle of the words before and the cell's exact adds (core/shared/packed_sums.h)
      const std::uint64_t before_count = history ? before->counts[slot] : 0;
      glm::uvec4 words(
          0u, 0u, 0u,
          shared::PackCountWord(std::uint32_t(before_count + cell.count), history ? before->frame_counters[slot] : 0u));
      for (int ch = 0; ch < 3; ++ch)
        words[ch] = std::uint32_t((history ? before->fixed_sums[slot][ch] : 0) + cell.fixed_sum[ch]);
      const glm::uvec4 settled = shared::SettlePacked(words);
      if (t.counts[slot] != shared::PackedCount(settled.w) ||
          t.fixed_sums[slot] != std::array<std::uint64_t, 3>{settled.x, settled.y, settled.z}) {
        verdict.Fail(record + ": count and sums differ from the settle of the slot before the frame and its cell's " +
                     std::to_string(cell.count) + " records");
      }
      continue;
    }
    const std::uint64_t count = t.counts[slot] - (history ? before->counts[slot] : 0);
    if (count != cell.count) {
      verdict.Fail(record + ": the frame's count " + std::to_string(count) + ", its cell's " +
                   std::to_string(cell.count));
      continue;
    }
    for (int ch = 0; ch < 3 && fixed; ++ch) {
      const std::uint64_t sum = t.fixed_sums[slot][ch] - (history ? before->fixed_sums[slot][ch] : 0);
      if (sum != cell.fixed_sum[ch]) {
        verdict.Fail(record + ": channel " + std::to_string(ch) + " differs from its cell's exact sum");
        break;
      }
    }
  }
  return compared;
}

}  // namespace hpsf
