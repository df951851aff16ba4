#include "tools/checks/table_checker.h"

#include <cmath>

#include "core/input_check.h"
#include "core/shared/fixed_point.h"

namespace hpsf {
namespace {

constexpr std::size_t kMaxRecordsNamed = 8;

std::string Records(const std::vector<std::uint32_t>& records) {
  std::string s;
  for (std::size_t i = 0; i < records.size() && i < kMaxRecordsNamed; ++i) s += (s.empty() ? "" : ", ") + std::to_string(records[i]);
  if (records.size() > kMaxRecordsNamed) s += ", ... (" + std::to_string(records.size()) + " in all)";
  return s;
}

}  // namespace

const char* ToString(TableInvariant invariant) {
  switch (invariant) {
    case TableInvariant::kPlacementOfUnkeyedRecord: return "placement of an unkeyed record";
    case TableInvariant::kSlotOutsideWindow: return "slot outside the probe window";
    case TableInvariant::kTagIsNotTheFingerprint: return "tag is not the record's fingerprint";
    case TableInvariant::kEarlierSlotEmptyOrMatching: return "earlier slot of the window empty or matching";
    case TableInvariant::kFailureWindowNotFull: return "probe failure with an empty or matching slot in its window";
    case TableInvariant::kCountMismatch: return "count differs from the records placed";
    case TableInvariant::kSumMismatch: return "sum differs from the records placed";
    case TableInvariant::kEmptySlotNotZero: return "empty slot with a count or sum";
    case TableInvariant::kOrphanTag: return "tag without a placed record";
    case TableInvariant::kTotalMismatch: return "table total differs from the placed contributions";
    case TableInvariant::kTagChangedAcrossFrames:
      return "slot claimed in an earlier frame lost its tag";
  }
  return "?";
}

std::string TableViolation::ToString() const {
  std::string s = hpsf::ToString(invariant);
  if (slot != 0xFFFFFFFFu) s += " at slot " + std::to_string(slot);
  if (!records.empty()) s += ", records " + Records(records);
  return detail.empty() ? s : s + ": " + detail;
}

std::vector<TableViolation> CheckTable(const TableCheckInput& in) {
  const HashTableDump& t = in.table;
  const std::uint32_t mask = t.capacity - 1u;
  const bool fixed = t.accumulation == Accumulation::kFixed64;
  const float scale = shared::PowerOfTwo(t.fixed_point_bits);
  std::vector<TableViolation> violations;
  // Before the frame: the earlier frames' tags, counts and sums (all zero for a table of this frame alone).
  const HashTableDump* before = in.before;
  auto tag_before = [&](std::uint32_t s) { return before ? before->tags[s] : kEmptyTag; };
  auto count_before = [&](std::uint32_t s) { return before ? before->counts[s] : 0; };
  // A dump holds the sums of its own mode only.
  auto fixed_before = [&](std::uint32_t s, int c) { return before && fixed ? before->fixed_sums[s][c] : 0; };
  auto float_before = [&](std::uint32_t s, int c) { return before && !fixed ? before->float_sums[s][c] : 0.0f; };
  auto violate = [&](TableInvariant invariant, std::uint32_t slot, std::vector<std::uint32_t> records, std::string detail) {
    violations.push_back({invariant, slot, std::move(records), std::move(detail)});
  };

  std::vector<std::vector<std::uint32_t>> placed(t.capacity);
  for (std::uint32_t i = 0; i < in.records.size(); ++i) {
    const KeyResult& key = in.keys[i];
    const std::uint32_t slot = in.placements[i];
    const bool keyed = key.status == shared::kKeyed && CheckRecordInputs(in.records[i]) == InputVerdict::kAccepted;
    if (!keyed || slot == kNotPlaced) {
      if (keyed != (slot != kNotPlaced)) violate(TableInvariant::kPlacementOfUnkeyedRecord, 0xFFFFFFFFu, {i}, keyed ? "keyed but never probed" : "placed without a key");
      continue;
    }
    if (slot == kProbeFailure) {
      for (std::uint32_t probe = 0; probe < t.probe_limit; ++probe) {
        const std::uint32_t s = (key.slot0 + probe) & mask;
        if (t.tags[s] == kEmptyTag || t.tags[s] == key.fingerprint) {
          violate(TableInvariant::kFailureWindowNotFull, s, {i}, "tag " + std::to_string(t.tags[s]) + " at probe " + std::to_string(probe));
          break;
        }
      }
      continue;
    }
    if (slot >= t.capacity) {
      violate(TableInvariant::kSlotOutsideWindow, slot, {i}, "slot beyond capacity " + std::to_string(t.capacity));
      continue;
    }
    const std::uint32_t distance = (slot - key.slot0) & mask;
    if (distance >= t.probe_limit) {
      violate(TableInvariant::kSlotOutsideWindow, slot, {i}, "slot0 " + std::to_string(key.slot0) + ", probe " + std::to_string(distance));
    }
    if (t.tags[slot] != key.fingerprint) {
      violate(TableInvariant::kTagIsNotTheFingerprint, slot, {i},
              "tag " + std::to_string(t.tags[slot]) + ", fingerprint " + std::to_string(key.fingerprint));
    }
    for (std::uint32_t probe = 0; probe < std::min(distance, t.probe_limit); ++probe) {
      const std::uint32_t s = (key.slot0 + probe) & mask;
      if (t.tags[s] == kEmptyTag || t.tags[s] == key.fingerprint) {
        violate(TableInvariant::kEarlierSlotEmptyOrMatching, s, {i}, "tag " + std::to_string(t.tags[s]) + " before slot " + std::to_string(slot));
        break;
      }
    }
    placed[slot].push_back(i);
  }

  // Per slot: counts, sums, empty slots, orphan tags; and the table totals. A slot's expected count and sums are
  // what it held before the frame plus what the frame placed there.
  std::array<unsigned __int128, 3> table_total{}, placed_total{};
  std::uint64_t total_count = 0, count_total_before = 0;
  for (std::uint32_t s = 0; s < t.capacity; ++s) {
    const std::vector<std::uint32_t>& here = placed[s];
    if (tag_before(s) != kEmptyTag && t.tags[s] != tag_before(s)) {
      violate(TableInvariant::kTagChangedAcrossFrames, s, here,
              "tag " + std::to_string(tag_before(s)) + " before the frame, " + std::to_string(t.tags[s]) + " after");
    }
    count_total_before += count_before(s);
    for (int c = 0; c < 3; ++c) placed_total[c] += fixed_before(s, c);
    if (t.tags[s] == kEmptyTag) {
      const bool sums_zero = fixed ? (t.fixed_sums[s] == std::array<std::uint64_t, 3>{}) : (t.float_sums[s] == std::array<float, 3>{});
      if (t.counts[s] != 0 || !sums_zero) violate(TableInvariant::kEmptySlotNotZero, s, here, "count " + std::to_string(t.counts[s]));
      continue;
    }
    if (here.empty() && tag_before(s) == kEmptyTag)
      violate(TableInvariant::kOrphanTag, s, {}, "tag " + std::to_string(t.tags[s]));
    if (t.counts[s] != count_before(s) + here.size()) {
      violate(TableInvariant::kCountMismatch, s, here,
              "count " + std::to_string(t.counts[s]) + ", before " + std::to_string(count_before(s)) + " + placed " +
                  std::to_string(here.size()));
    }
    total_count += t.counts[s];
    for (int c = 0; c < 3; ++c) {
      unsigned __int128 exact = fixed_before(s, c);
      double exact_float = double(float_before(s, c)), magnitude = std::abs(exact_float);
      for (std::uint32_t i : here) {
        const float v = in.records[i].contribution[c];
        exact += shared::ToFixedPoint(v, scale);
        exact_float += double(v);
        magnitude += std::abs(double(v));
      }
      if (fixed) {
        table_total[c] += t.fixed_sums[s][c];
        placed_total[c] += exact - fixed_before(s, c);
        if (exact != t.fixed_sums[s][c]) {
          violate(TableInvariant::kSumMismatch, s, here, "channel " + std::to_string(c) + ": sum " + std::to_string(t.fixed_sums[s][c]) +
                                                              ", exact " + std::to_string(std::uint64_t(exact)));
        }
      } else {
        // Float atomics are not promised to round to nearest: u = 2^-23, gamma(k) = k u / (1 - k u), over the k
        // adds after the first term (the sum before the frame counts as one when there is one).
        const std::size_t terms = here.size() + (count_before(s) > 0 ? 1 : 0);
        const double k = double(terms > 0 ? terms - 1 : 0), u = 0x1p-23;
        const double bound = k * u / (1.0 - k * u) * magnitude;
        if (!(std::abs(double(t.float_sums[s][c]) - exact_float) <= bound)) {
          violate(TableInvariant::kSumMismatch, s, here, "channel " + std::to_string(c) + ": sum " + std::to_string(t.float_sums[s][c]) +
                                                              ", exact " + std::to_string(exact_float) + ", bound " + std::to_string(bound));
        }
      }
    }
  }
  std::uint64_t placed_count = 0;
  for (const auto& here : placed) placed_count += here.size();
  if (total_count != count_total_before + placed_count) {
    violate(TableInvariant::kTotalMismatch, 0xFFFFFFFFu, {},
            "count " + std::to_string(total_count) + ", before " + std::to_string(count_total_before) + " + placed " +
                std::to_string(placed_count));
  }
  for (int c = 0; c < 3; ++c) {
    if (fixed && table_total[c] != placed_total[c]) {
      violate(TableInvariant::kTotalMismatch, 0xFFFFFFFFu, {}, "channel " + std::to_string(c) + " total differs");
    }
  }
  return violations;
}

}  // namespace hpsf
