#include "verifier/checker/table_checker.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "core/input_check.h"
#include "core/level_touches.h"
#include "core/shared/eviction_priority.h"
#include "core/shared/fixed_point.h"
#include "core/shared/levels.h"
#include "core/shared/packed_sums.h"
#include "core/shared/second_moment.h"

namespace hpsf {
namespace {

constexpr std::size_t kMaxRecordsNamed = 8;

std::string Records(const std::vector<std::uint32_t>& records) {
  std::string s;
  for (std::size_t i = 0; i < records.size() && i < kMaxRecordsNamed; ++i)
    s += (s.empty() ? "" : ", ") + std::to_string(records[i]);
  if (records.size() > kMaxRecordsNamed) s += ", ... (" + std::to_string(records.size()) + " in all)";
  return s;
}

// Touch t adds record t mod n at t / n levels above its own cell (core/shared/levels.h): t = i with one level.
const Record& RecordOf(const TableCheckInput& in, std::uint32_t touch) { return in.records[touch % in.records.size()]; }

std::vector<std::uint32_t> RecordsOf(const TableCheckInput& in, std::vector<std::uint32_t> touches) {
  for (std::uint32_t& t : touches) t = static_cast<std::uint32_t>(t % in.records.size());
  return touches;
}

std::string Decimal(unsigned __int128 x) {
  std::string digits;
  do {
    digits.insert(digits.begin(), char('0' + int(x % 10)));
    x /= 10;
  } while (x != 0);
  return digits;
}

std::string SumsText(const std::array<std::uint64_t, 3>& sums) {
  return "(" + std::to_string(sums[0]) + ", " + std::to_string(sums[1]) + ", " + std::to_string(sums[2]) + ")";
}

// A slot the frame added to that held samples before it, under a blending temporal mode.
void CheckBlend(const TableCheckInput& in, std::uint32_t s, const std::vector<std::uint32_t>& here,
                const CellState& before, std::vector<TableViolation>& violations) {
  const HashTableDump& t = in.table;
  const bool fixed = t.accumulation == Accumulation::kFixed64;
  const float scale = shared::PowerOfTwo(t.fixed_point_bits);
  const shared::TemporalParams params =
      MakeTemporalParams(in.temporal, t.accumulation, t.fixed_point_bits, t.square_bits);
  auto fail = [&](std::string detail) {
    violations.push_back({TableInvariant::kTemporalBlend, s, RecordsOf(in, here), std::move(detail)});
  };
  CellState accumulated = before;
  accumulated.count += here.size();
  std::array<double, 3> frame_exact{};
  double frame_square_exact = 0.0;
  const double square_scale = std::ldexp(1.0, t.square_bits);
  for (std::uint32_t i : here) {
    const glm::vec3 contribution(RecordOf(in, i).contribution);
    for (int c = 0; c < 3; ++c) {
      const float v = contribution[c];
      accumulated.fixed_sum[c] += shared::ToFixedPoint(v, scale);
      frame_exact[c] += double(v);
    }
    if (t.second_moments) {
      accumulated.fixed_square += shared::SquareToFixedPoint(contribution, square_scale);
      frame_square_exact += double(shared::SquareAsFloat(contribution));
    }
  }
  if (fixed) {
    const CellState expected = BlendCellState(params, Accumulation::kFixed64, before, accumulated);
    if (t.counts[s] != expected.count || t.fixed_sums[s] != expected.fixed_sum) {
      fail("count " + std::to_string(t.counts[s]) + ", sums " + SumsText(t.fixed_sums[s]) + "; the blend of count " +
           std::to_string(before.count) + " + " + std::to_string(here.size()) + " gives count " +
           std::to_string(expected.count) + ", sums " + SumsText(expected.fixed_sum));
    }
    if (t.second_moments && t.fixed_squares[s] != expected.fixed_square) {
      violations.push_back({TableInvariant::kSquareSumMismatch, s, RecordsOf(in, here),
                            "square sum " + std::to_string(t.fixed_squares[s]) + "; the blend of count " +
                                std::to_string(before.count) + " + " + std::to_string(here.size()) + " gives " +
                                std::to_string(expected.fixed_square)});
    }
    return;
  }
  // float32: the backend's frame sums carry the rounding of its adds, so the blend is bounded, not replayed. ema's
  // alpha, and so the count, does not depend on the sums; adaptive's lies between forgetting and integrating.
  for (int c = 0; c < 3; ++c) accumulated.float_sum[c] = float(double(before.float_sum[c]) + frame_exact[c]);
  const CellState by_exact = BlendCellState(params, Accumulation::kFloat32, before, accumulated);
  const std::uint64_t n = here.size();
  const std::uint64_t most = std::min(before.count, params.max_count) + n;
  const bool count_ok =
      in.temporal.mode == TemporalMode::kEma ? t.counts[s] == by_exact.count : t.counts[s] >= n && t.counts[s] <= most;
  if (!count_ok) {
    fail("count " + std::to_string(t.counts[s]) + ", expected " +
         (in.temporal.mode == TemporalMode::kEma ? std::to_string(by_exact.count)
                                                 : "[" + std::to_string(n) + ", " + std::to_string(most) + "]"));
  }
  // The frame's sum is (history + adds) - history in float: each of the n adds and the subtraction rounds by at
  // most u of a running total no larger than the final one.
  const double u = 0x1p-23, k = double(n + 1), gamma = k * u / (1.0 - k * u);
  for (int c = 0; c < 3; ++c) {
    const double history = double(before.float_sum[c]) / double(before.count);
    const double error = gamma * (double(before.float_sum[c]) + frame_exact[c]);
    const double frame_low = (frame_exact[c] - error) / double(n), frame_high = (frame_exact[c] + error) / double(n);
    // Widened for the blend's double arithmetic and the sum's rounding to float.
    const double low = std::min(history, frame_low) * (1.0 - 4 * u);
    const double high = std::max(history, frame_high) * (1.0 + 4 * u);
    const double average = t.counts[s] ? double(t.float_sums[s][c]) / double(t.counts[s]) : 0.0;
    if (!(average >= low && average <= high)) {
      fail("channel " + std::to_string(c) + ": average " + std::to_string(average) + " outside [" +
           std::to_string(low) + ", " + std::to_string(high) + "], the history's and the frame's");
    }
  }
  if (!t.second_moments) return;
  // The mean square, held as the averages are: between the history's and the frame's.
  const double history = double(before.float_square) / double(before.count);
  const double error = gamma * (double(before.float_square) + frame_square_exact);
  const double low = std::min(history, (frame_square_exact - error) / double(n)) * (1.0 - 4 * u);
  const double high = std::max(history, (frame_square_exact + error) / double(n)) * (1.0 + 4 * u);
  const double mean_square = t.counts[s] ? double(t.float_squares[s]) / double(t.counts[s]) : 0.0;
  if (!(mean_square >= low && mean_square <= high)) {
    violations.push_back({TableInvariant::kSquareSumMismatch, s, RecordsOf(in, here),
                          "mean square " + std::to_string(mean_square) + " outside [" + std::to_string(low) + ", " +
                              std::to_string(high) + "], the history's and the frame's"});
  }
}

// packed-decimal under a blending temporal mode: the words a slot blends to before its settle, from its words before
// the frame and its exact words after the adds (both in range). The blend is fixed64's on those words, exact; a
// blended word past 32 bits (a count past 24) is kept modulo them by the device, as a wrapped add, and named.
glm::uvec4 BlendPacked(const TableCheckInput& in, std::uint32_t s, const std::vector<std::uint32_t>& here,
                       const std::array<std::uint64_t, 3>& old_sums, std::uint64_t old_count, glm::uvec4 accumulated,
                       std::vector<TableViolation>& violations) {
  const CellState before{old_sums, {}, old_count};
  const CellState added{{accumulated.x, accumulated.y, accumulated.z}, {}, shared::PackedCount(accumulated.w)};
  const CellState wide = BlendCellState(MakeTemporalParams(in.temporal, Accumulation::kPackedDecimal, 0, 0),
                                        Accumulation::kFixed64, before, added);
  for (int c = 0; c < 3; ++c) {
    if (wide.fixed_sum[c] > 0xFFFFFFFFu) {
      violations.push_back({TableInvariant::kTemporalBlend, s, RecordsOf(in, here),
                            "channel " + std::to_string(c) + ": the blend's sum " + std::to_string(wide.fixed_sum[c]) +
                                " does not fit packed-decimal's 32 bits"});
    }
  }
  if (wide.count > shared::kPackedCountMask) {
    violations.push_back(
        {TableInvariant::kTemporalBlend, s, RecordsOf(in, here),
         "the blend's count " + std::to_string(wide.count) + " does not fit packed-decimal's 24 bits"});
  }
  return {
      std::uint32_t(wide.fixed_sum[0]), std::uint32_t(wide.fixed_sum[1]), std::uint32_t(wide.fixed_sum[2]),
      shared::PackCountWord(std::uint32_t(wide.count) & shared::kPackedCountMask, shared::PackedFrames(accumulated.w))};
}

// With compaction: the list holds each slot whose tag is set once, and nothing else (Bevy #21904 listed a cell with
// none active). The first eight offences are named, then how many more there are.
void CheckOccupiedList(const HashTableDump& t, std::vector<TableViolation>& violations) {
  constexpr int kNamed = 8;
  int named = 0;
  auto fail = [&](std::uint32_t slot, std::string detail) {
    if (named++ < kNamed) violations.push_back({TableInvariant::kOccupiedList, slot, {}, std::move(detail)});
  };
  if (t.occupied.size() > t.capacity) {
    fail(0xFFFFFFFFu, "the list's count " + std::to_string(t.occupied.size()) + " exceeds the " +
                          std::to_string(t.capacity) + " slots");
  }
  std::vector<std::uint8_t> seen(t.capacity, 0);
  for (std::size_t entry = 0; entry < t.occupied.size(); ++entry) {
    const std::uint32_t slot = t.occupied[entry];
    if (slot >= t.capacity) {
      fail(0xFFFFFFFFu,
           "entry " + std::to_string(entry) + " names slot " + std::to_string(slot) + ", past the table's end");
    } else if (seen[slot]) {
      fail(slot, "entry " + std::to_string(entry) + " lists it again");
    } else {
      seen[slot] = 1;
      if (t.tags[slot] == kEmptyTag) fail(slot, "entry " + std::to_string(entry) + " lists it, but it is empty");
    }
  }
  for (std::uint32_t slot = 0; slot < t.capacity; ++slot) {
    if (t.tags[slot] != kEmptyTag && !seen[slot])
      fail(slot, "occupied (tag " + std::to_string(t.tags[slot]) + "), but not in the list of " +
                     std::to_string(t.occupied.size()));
  }
  if (named > kNamed) {
    violations.push_back({TableInvariant::kOccupiedList,
                          0xFFFFFFFFu,
                          {},
                          std::to_string(named - kNamed) + " more entries or slots not named"});
  }
}

// --levels: the frame's adds nest (core/shared/levels.h). What it added to a coarser cell's slot is what it added to
// its children's slots, less the adds of records whose coarsest level the child is, plus the records whose own cell it
// is. Judged where the relation is exact: each slot involved unaliased, every touch that should reach the parent
// placed there, and no slot blended (fixed64: counts and sums; float32: counts; packed-decimal, whose settle may halve,
// and blended slots are judged by their own invariants only).
// seeds: per slot, the seed a new slot started from (core/level_seed.h), which is no child's add.
void CheckLevelNesting(const TableCheckInput& in, const LevelTouches& touches, const std::vector<CellState>& seeds,
                       std::vector<TableViolation>& violations) {
  const HashTableDump& t = in.table;
  const HashTableDump* before = in.before;
  if (t.accumulation == Accumulation::kPackedDecimal) return;
  const bool fixed = t.accumulation == Accumulation::kFixed64;
  const float scale = SumScale(t.accumulation, t.fixed_point_bits);
  const std::size_t n = in.records.size();
  const std::size_t coarsest = std::size_t(t.levels - 1) * n;  // the first touch of the coarsest level
  struct Adds {
    std::vector<std::uint32_t> touches;
    std::optional<std::array<std::uint32_t, 6>> key;
    bool aliased = false;
  };
  std::vector<Adds> at(t.capacity);
  for (std::uint32_t i = 0; i < touches.size(); ++i) {
    const std::uint32_t slot = touches.placements()[i];
    if (slot >= t.capacity) continue;
    const shared::KeyWords& w = touches.keys()[i].words;
    const std::array<std::uint32_t, 6> key = {w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra};
    at[slot].aliased |= at[slot].key && *at[slot].key != key;
    at[slot].key = key;
    at[slot].touches.push_back(i);
  }
  auto blended = [&](std::uint32_t s) { return in.temporal.blends() && before && before->counts[s] > 0; };
  using Sums = std::array<__int128, 4>;  // the count, then the three fixed64 sums
  auto delta = [&](std::uint32_t s) {
    Sums d{__int128(t.counts[s]) - __int128(before ? before->counts[s] : 0) - __int128(seeds[s].count)};
    for (int c = 0; c < 3 && fixed; ++c) {
      d[c + 1] = __int128(t.fixed_sums[s][c]) - __int128(before ? before->fixed_sums[s][c] : 0) -
                 __int128(seeds[s].fixed_sum[c]);
    }
    return d;
  };
  auto add = [&](Sums& sums, std::uint32_t touch, int sign) {
    sums[0] += sign;
    for (int c = 0; c < 3 && fixed; ++c)
      sums[c + 1] += sign * __int128(shared::ToFixedPoint(RecordOf(in, touch).contribution[c], scale));
  };
  for (std::uint32_t parent = 0; parent < t.capacity; ++parent) {
    const Adds& here = at[parent];
    if (here.touches.empty() || here.aliased || blended(parent)) continue;
    Sums expected{};
    std::vector<std::uint32_t> children;
    bool exact = true;
    for (const std::uint32_t touch : here.touches) {
      if (touch < n) {
        add(expected, touch, +1);  // the record's own cell
        continue;
      }
      const std::uint32_t child = touches.placements()[touch - n];
      if (child >= t.capacity) exact = false;  // the child's add failed: the parent holds more than its children
      if (exact && std::find(children.begin(), children.end(), child) == children.end()) children.push_back(child);
    }
    for (const std::uint32_t child : children) {
      if (!exact) break;
      if (at[child].aliased || blended(child)) exact = false;
      const Sums d = delta(child);
      for (int w = 0; w < 4; ++w) expected[w] += d[w];
      for (const std::uint32_t touch : at[child].touches) {
        if (touch >= coarsest) {
          add(expected, touch, -1);  // the record's coarsest level: it reaches no parent
        } else if (touches.placements()[touch + n] != parent) {
          exact = false;  // a record of the child that went elsewhere (failed): judged by the placement checks
        }
      }
    }
    if (!exact) continue;
    const Sums got = delta(parent);
    if (got == expected) continue;
    const int word = got[0] != expected[0] ? 0 : got[1] != expected[1] ? 1 : got[2] != expected[2] ? 2 : 3;
    std::string detail = word == 0 ? "the frame added count " + Decimal(std::uint64_t(got[0])) + ", its children " +
                                         Decimal(std::uint64_t(expected[0]))
                                   : "channel " + std::to_string(word - 1) + ": the frame added " +
                                         Decimal(std::uint64_t(got[word])) + ", its children " +
                                         Decimal(std::uint64_t(expected[word]));
    std::string listed;
    for (const std::uint32_t child : children) listed += (listed.empty() ? "" : ", ") + std::to_string(child);
    violations.push_back(
        {TableInvariant::kLevelNesting, parent, RecordsOf(in, here.touches), detail + " (child slots " + listed + ")"});
  }
}

}  // namespace

const char* ToString(TableInvariant invariant) {
  switch (invariant) {
    case TableInvariant::kPlacementOfUnkeyedRecord:
      return "placement of an unkeyed record";
    case TableInvariant::kSlotOutsideWindow:
      return "slot outside the probe window";
    case TableInvariant::kTagIsNotTheFingerprint:
      return "tag is not the record's fingerprint";
    case TableInvariant::kEarlierSlotEmptyOrMatching:
      return "earlier slot of the window empty or matching";
    case TableInvariant::kFailureWindowNotFull:
      return "probe failure with an empty, matching or claimable slot in its window";
    case TableInvariant::kCountMismatch:
      return "count differs from the records placed";
    case TableInvariant::kSumMismatch:
      return "sum differs from the records placed";
    case TableInvariant::kEmptySlotNotZero:
      return "empty slot with a count or sum";
    case TableInvariant::kOrphanTag:
      return "tag without a placed record";
    case TableInvariant::kTotalMismatch:
      return "table total differs from the placed contributions";
    case TableInvariant::kTagChangedAcrossFrames:
      return "slot claimed in an earlier frame lost its tag";
    case TableInvariant::kEvictionPolicy:
      return "eviction differs from the policy";
    case TableInvariant::kLastSeenWrong:
      return "last-seen frame wrong";
    case TableInvariant::kHoleBeforeLiveSlot:
      return "tombstone emptied before a live slot that may need it";
    case TableInvariant::kTombstoneKept:
      return "tombstone kept that no live slot needs";
    case TableInvariant::kTemporalBlend:
      return "blended cell differs from the temporal blend";
    case TableInvariant::kCellSplit:
      return "slot claimed though the cell lived in the window before the frame";
    case TableInvariant::kOccupiedList:
      return "occupied list differs from the occupied slots";
    case TableInvariant::kPackedSettle:
      return "packed-decimal slot differs from the settle of its exact sums";
    case TableInvariant::kLevelNesting:
      return "coarser cell differs from the children that reach it";
    case TableInvariant::kSquareSumMismatch:
      return "square sum differs from the records placed";
  }
  return "?";
}

std::string TableViolation::ToString() const {
  std::string s = hpsf::ToString(invariant);
  if (slot != 0xFFFFFFFFu) s += " at slot " + std::to_string(slot);
  if (!records.empty()) s += ", records " + Records(records);
  return detail.empty() ? s : s + ": " + detail;
}

std::vector<TableViolation> CheckOccupiedListOf(const HashTableDump& table) {
  std::vector<TableViolation> violations;
  CheckOccupiedList(table, violations);
  return violations;
}

std::vector<TableViolation> CheckTable(const TableCheckInput& in) {
  const HashTableDump& t = in.table;
  const shared::ProbeScheme scheme = ProbeSchemeOf(t);
  const bool fixed = IntegerSums(t.accumulation);  // fixed64 or packed-decimal: exact
  const bool packed = t.accumulation == Accumulation::kPackedDecimal;
  const float scale = SumScale(t.accumulation, t.fixed_point_bits);
  std::vector<TableViolation> violations;
  const bool squares = t.second_moments;
  if (squares &&
      ((fixed ? t.fixed_squares.size() : t.float_squares.size()) != t.capacity ||
       (in.before && (!in.before->second_moments ||
                      (fixed ? in.before->fixed_squares.size() : in.before->float_squares.size()) != t.capacity)))) {
    violations.push_back(
        {TableInvariant::kSquareSumMismatch, 0xFFFFFFFFu, {}, "a table without a square sum per slot"});
    return violations;
  }
  const double square_scale = std::ldexp(1.0, t.square_bits);
  if (packed &&
      (t.frame_counters.size() != t.capacity || (in.before && in.before->frame_counters.size() != t.capacity))) {
    violations.push_back({TableInvariant::kPackedSettle, 0xFFFFFFFFu, {}, "a table without a frame counter per slot"});
    return violations;
  }
  // Before the frame: the earlier frames' tags, counts and sums (all zero for a table of this frame alone).
  const HashTableDump* before = in.before;
  auto tag_before = [&](std::uint32_t s) { return before ? before->tags[s] : kEmptyTag; };
  auto count_before = [&](std::uint32_t s) { return before ? before->counts[s] : 0; };
  // A dump holds the sums of its own mode only.
  auto fixed_before = [&](std::uint32_t s, int c) { return before && fixed ? before->fixed_sums[s][c] : 0; };
  auto float_before = [&](std::uint32_t s, int c) { return before && !fixed ? before->float_sums[s][c] : 0.0f; };
  auto fixed_square_before = [&](std::uint32_t s) -> std::uint64_t {
    return squares && before && fixed ? before->fixed_squares[s] : 0;
  };
  auto float_square_before = [&](std::uint32_t s) {
    return squares && before && !fixed ? before->float_squares[s] : 0.0f;
  };
  auto violate = [&](TableInvariant invariant, std::uint32_t slot, std::vector<std::uint32_t> records,
                     std::string detail) {
    violations.push_back({invariant, slot, RecordsOf(in, std::move(records)), std::move(detail)});
  };
  if (t.compacted) CheckOccupiedList(t, violations);

  // The tags the frame's lookups saw: with eviction, a tombstone the reclaim emptied after them still held its tag
  // (whether the reclaim was right to empty it is the tombstone check's question below).
  // With priority eviction a slot tagged kTombstoneTag after the frame was a live victim during it, or a tombstone
  // before it; either way it held its tag from before.
  const bool evicting = in.eviction.enabled();
  const bool priority = in.eviction.by_priority();
  auto tombstone_tag = [&](SlotTag tag) { return priority && tag == shared::kTombstoneTag; };
  auto window_tag = [&](std::uint32_t s) {
    return evicting && (t.tags[s] == kEmptyTag || tombstone_tag(t.tags[s])) ? tag_before(s) : t.tags[s];
  };
  // Per slot, the touches placed there: with one level, the records.
  const LevelTouches touches(t, in.keys, in.placements, in.coarser_placements, in.normal_in_index);
  std::vector<std::vector<std::uint32_t>> placed(t.capacity);
  std::vector<bool> claimed_cleanly(t.capacity, false);     // a new cell's slot, reached by a touch past no tombstone
  std::map<std::uint32_t, std::uint32_t> tombstone_passed;  // touch -> the tombstone before its new cell's slot
  for (std::uint32_t i = 0; i < touches.size(); ++i) {
    const KeyResult& key = touches.keys()[i];
    const SlotTag identity = StoredIdentity(key);  // a fingerprint, or a full key (core/key_identity.h)
    const std::uint32_t slot = touches.placements()[i];
    const bool keyed = key.status == shared::kKeyed && CheckRecordInputs(RecordOf(in, i)) == InputVerdict::kAccepted;
    if (!keyed || slot == kNotPlaced) {
      if (keyed != (slot != kNotPlaced))
        violate(TableInvariant::kPlacementOfUnkeyedRecord, 0xFFFFFFFFu, {i},
                keyed ? "keyed but never probed" : "placed without a key");
      continue;
    }
    // Candidates are walked from slot0: one past the table names no slot (a scheme other than linear does not
    // mask it back in), so it is the violation, and nothing else of the record is judged.
    if (key.slot0 >= t.capacity) {
      violate(TableInvariant::kSlotOutsideWindow, slot, {i},
              "slot0 " + std::to_string(key.slot0) + " is not below the capacity " + std::to_string(t.capacity));
      continue;
    }
    if (slot == kProbeFailure) {
      for (std::uint32_t probe = 0; probe < t.probe_limit; ++probe) {
        const std::uint32_t s = shared::CandidateSlot(scheme, key.slot0, probe);
        if (window_tag(s) == kEmptyTag || window_tag(s) == identity || tombstone_tag(window_tag(s))) {
          violate(TableInvariant::kFailureWindowNotFull, s, {i},
                  "tag " + std::to_string(window_tag(s)) + " at probe " + std::to_string(probe));
          break;
        }
      }
      continue;
    }
    if (slot >= t.capacity) {
      violate(TableInvariant::kSlotOutsideWindow, slot, {i}, "slot beyond capacity " + std::to_string(t.capacity));
      continue;
    }
    const std::uint32_t distance = shared::ProbeIndex(scheme, key.slot0, slot);
    if (distance == shared::kNoCandidate) {
      violate(TableInvariant::kSlotOutsideWindow, slot, {i},
              "slot0 " + std::to_string(key.slot0) + ", not among its " + ToString(t.probing) + ":" +
                  std::to_string(t.probe_limit) + " candidates");
    }
    if (t.tags[slot] != identity) {
      violate(TableInvariant::kTagIsNotTheFingerprint, slot, {i},
              "tag " + std::to_string(t.tags[slot]) +
                  (t.key_identity == KeyIdentity::kFull ? ", full key " : ", fingerprint ") + std::to_string(identity));
    }
    // With priority, an insertion claims the first tombstone, but a cell that lived before the frame is found past
    // one.
    const bool new_cell = tag_before(slot) != identity;
    // A live slot holding the fingerprint before the frame, with no empty slot before it in the window, is where
    // the record belongs (its cell, or an alias): a record that claimed another slot split it (past a priority
    // tombstone). Past an empty slot it may be an alias from another slot0 (D7's hole the reclaim check catches).
    for (std::uint32_t probe = 0; new_cell && probe < t.probe_limit; ++probe) {
      const std::uint32_t s = shared::CandidateSlot(scheme, key.slot0, probe);
      if (tag_before(s) == kEmptyTag) break;
      if (s != slot && tag_before(s) == identity && count_before(s) > 0) {
        violate(TableInvariant::kCellSplit, slot, {i}, "the fingerprint lived at slot " + std::to_string(s));
        break;
      }
    }
    bool past_tombstone = false;
    for (std::uint32_t probe = 0; probe < std::min(distance, t.probe_limit); ++probe) {
      const std::uint32_t s = shared::CandidateSlot(scheme, key.slot0, probe);
      const SlotTag seen = window_tag(s);
      if (seen == kEmptyTag || seen == identity) {
        violate(TableInvariant::kEarlierSlotEmptyOrMatching, s, {i},
                "tag " + std::to_string(window_tag(s)) + " before slot " + std::to_string(slot));
        break;
      }
      if (new_cell && tombstone_tag(seen) && !past_tombstone) {
        past_tombstone = true;
        tombstone_passed[i] = s;
      }
    }
    if (new_cell && !past_tombstone) claimed_cleanly[slot] = true;
    placed[slot].push_back(i);
  }
  // A new cell's slot past a tombstone of its window: right only where it joined the slot, which some touch whose
  // window reaches it without a tombstone (one with another slot0) claimed this frame; the first loop of the
  // priority insertion finds its identity anywhere up to the first empty slot, an alias among them.
  for (const auto& [i, s] : tombstone_passed) {
    const std::uint32_t slot = touches.placements()[i];
    if (claimed_cleanly[slot]) continue;
    violate(TableInvariant::kEarlierSlotEmptyOrMatching, s, {i},
            "tag " + std::to_string(window_tag(s)) + " before slot " + std::to_string(slot));
  }

  // Eviction: the state the policy leaves between the evict and the reclaim passes (the snapshot), from the table
  // before, this frame's placements and the last-seen frames alone.
  const Eviction& eviction = in.eviction;
  if (evicting && (t.last_seen.size() != t.capacity || (before && before->last_seen.size() != t.capacity))) {
    violate(TableInvariant::kLastSeenWrong, 0xFFFFFFFFu, {}, "a table without a last-seen frame per slot");
    return violations;
  }
  auto last_seen_before = [&](std::uint32_t s) { return before && evicting ? before->last_seen[s] : 0u; };
  // Priority: in the window of each record that found no slot, the untouched live slot of lowest priority.
  std::vector<std::uint32_t> victim_of(priority ? t.capacity : 0, kNotPlaced);  // per slot, a record choosing it
  for (std::uint32_t i = 0; priority && i < touches.size(); ++i) {
    if (touches.placements()[i] != kProbeFailure || touches.keys()[i].slot0 >= t.capacity) continue;
    std::optional<std::uint32_t> victim;
    for (std::uint32_t probe = 0; probe < t.probe_limit; ++probe) {
      const std::uint32_t s = shared::CandidateSlot(scheme, touches.keys()[i].slot0, probe);
      if (!placed[s].empty() || tag_before(s) == kEmptyTag || tombstone_tag(tag_before(s)) || count_before(s) == 0)
        continue;
      auto priority_of = [&](std::uint32_t slot) {
        return shared::EvictionPriority(last_seen_before(slot), count_before(slot));
      };
      if (!victim || shared::EvictedBefore(priority_of(s), tag_before(s), priority_of(*victim), tag_before(*victim)))
        victim = s;
    }
    if (victim && victim_of[*victim] == kNotPlaced) victim_of[*victim] = i;
  }
  auto evicted_now = [&](std::uint32_t s) {
    return evicting && placed[s].empty() && tag_before(s) != kEmptyTag && count_before(s) > 0 &&
           (priority ? victim_of[s] != kNotPlaced : eviction.Evicts(in.frame, last_seen_before(s)));
  };
  auto snapshot_tag = [&](std::uint32_t s) { return placed[s].empty() ? tag_before(s) : t.tags[s]; };
  auto snapshot_live = [&](std::uint32_t s) {
    return snapshot_tag(s) != kEmptyTag && (!placed[s].empty() || (count_before(s) > 0 && !evicted_now(s)));
  };
  // A tombstone is kept exactly when a live slot follows it in some key's candidate order with no empty slot between.
  auto live_slot_after = [&](std::uint32_t s) -> std::uint32_t {
    for (std::uint32_t distance = 1;; ++distance) {
      const std::uint32_t next = shared::SlotAfter(scheme, s, distance);
      if (next == shared::kNoCandidate) break;
      if (snapshot_tag(next) == kEmptyTag) break;
      if (snapshot_live(next)) return next;
    }
    return 0xFFFFFFFFu;
  };

  // The seed of a slot new this frame, from the table before it: of the cell its records key (of whichever of an
  // aliased slot's cells gives the count found; the backends seed from the one record that claims the seeding).
  auto SeedOfSlot = [&](std::uint32_t s, const std::vector<std::uint32_t>& here) {
    CellState chosen;
    if (!in.level_seed.enabled || !before || here.empty() || count_before(s) != 0) return chosen;
    const CellLookup lookup = [&](const shared::KeyWords& w) { return FindInTable(*before, w, in.normal_in_index); };
    std::set<std::array<std::uint32_t, 6>> tried;
    for (std::size_t n = 0; n < here.size(); ++n) {
      const shared::KeyWords& w = touches.keys()[here[n]].words;
      if (!tried.insert({w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra}).second) continue;
      const CellState seed = SeedOf(w, in.level_seed, fixed, lookup);
      if (n == 0 || seed.count + here.size() == t.counts[s]) chosen = seed;
    }
    return chosen;
  };

  // Per slot: counts, sums, empty slots, orphan tags; and the table totals. A slot's expected count and sums are
  // what it held before the frame (nothing, if the policy evicts it now) plus what the frame placed there.
  std::array<unsigned __int128, 3> table_total{}, placed_total{};
  unsigned __int128 table_square_total = 0, placed_square_total = 0;
  std::vector<CellState> seeds(t.levels > 1 ? t.capacity : 0);  // for the level nesting
  // Counts in 128 bits: a 64-bit count that wrapped (D12) must not look right because the checker's sum wrapped too.
  unsigned __int128 total_count = 0, expected_total_count = 0;
  auto sums_are_zero = [&](std::uint32_t s) {
    if (packed && t.frame_counters[s] != 0) return false;
    if (squares && (fixed ? t.fixed_squares[s] != 0 : t.float_squares[s] != 0.0f)) return false;
    return fixed ? (t.fixed_sums[s] == std::array<std::uint64_t, 3>{}) : (t.float_sums[s] == std::array<float, 3>{});
  };
  for (std::uint32_t s = 0; s < t.capacity; ++s) {
    const std::vector<std::uint32_t>& here = placed[s];
    if (evicting && t.last_seen[s] != (here.empty() ? last_seen_before(s) : in.frame)) {
      violate(TableInvariant::kLastSeenWrong, s, here,
              "last seen " + std::to_string(t.last_seen[s]) + ", frame " + std::to_string(in.frame) +
                  (here.empty() ? ", untouched, before " + std::to_string(last_seen_before(s)) : ", touched"));
    }
    if (evicting && snapshot_tag(s) != kEmptyTag && !snapshot_live(s)) {
      const std::uint32_t live = live_slot_after(s);
      const SlotTag tombstone = priority ? shared::kTombstoneTag : snapshot_tag(s);
      const SlotTag expected = live != 0xFFFFFFFFu ? tombstone : kEmptyTag;
      // A priority victim left live keeps its tag: the policy check below reports it, once.
      const bool left_live = priority && t.tags[s] == snapshot_tag(s) && t.counts[s] != 0;
      if (t.tags[s] != expected && !left_live) {
        const TableInvariant invariant = t.tags[s] == kEmptyTag   ? TableInvariant::kHoleBeforeLiveSlot
                                         : t.tags[s] == tombstone ? TableInvariant::kTombstoneKept
                                                                  : TableInvariant::kTagChangedAcrossFrames;
        violate(
            invariant, s, here,
            "tombstone of tag " + std::to_string(snapshot_tag(s)) + ", tag " + std::to_string(t.tags[s]) + " after; " +
                (live != 0xFFFFFFFFu ? "live slot " + std::to_string(live) + " after it" : "no live slot after it"));
      }
    } else if (tag_before(s) != kEmptyTag && t.tags[s] != tag_before(s) &&
               !(tombstone_tag(tag_before(s)) && !here.empty()) &&
               !(tombstone_tag(t.tags[s]) && here.empty() && count_before(s) > 0)) {
      // (With priority, a tombstone claimed this frame takes its claimant's tag, and a live slot evicted the
      // policy's tag, which the policy check below judges.)
      violate(TableInvariant::kTagChangedAcrossFrames, s, here,
              "tag " + std::to_string(tag_before(s)) + " before the frame, " + std::to_string(t.tags[s]) + " after");
    }
    const bool evicted_by_policy = evicted_now(s);
    const bool looks_evicted = t.counts[s] == 0 && sums_are_zero(s);
    if (evicting && here.empty() && tag_before(s) != kEmptyTag && count_before(s) > 0 &&
        evicted_by_policy != looks_evicted) {
      const std::string why =
          !priority ? "last seen in frame " + std::to_string(last_seen_before(s)) + ", policy " + eviction.ToString() +
                          " after frame " + std::to_string(in.frame)
          : evicted_by_policy
              ? "the lowest priority in the window of record " + std::to_string(victim_of[s]) +
                    ", which found no slot: priority"
              : "not the lowest priority in the window of any record that found no slot (last seen " +
                    std::to_string(last_seen_before(s)) + ", count " + std::to_string(count_before(s)) + "): priority";
      violate(TableInvariant::kEvictionPolicy, s, {},
              why + (evicted_by_policy ? " evicts it, but it holds count " + std::to_string(t.counts[s])
                                       : " keeps it, but it was emptied"));
      continue;  // reported once: its count and sums are the policy's question, not the accumulate's
    }
    // A slot new this frame may start from its seed (core/level_seed.h) instead of nothing.
    const CellState seed = SeedOfSlot(s, here);
    if (t.levels > 1) seeds[s] = seed;
    const std::uint64_t base_count = evicted_by_policy ? 0 : count_before(s) + seed.count;
    auto fixed_base = [&](int c) -> std::uint64_t {
      return evicted_by_policy ? 0 : fixed_before(s, c) + seed.fixed_sum[c];
    };
    auto float_base = [&](int c) -> float { return evicted_by_policy ? 0.0f : float_before(s, c) + seed.float_sum[c]; };
    if (t.tags[s] == kEmptyTag) {
      if (t.counts[s] != 0 || !sums_are_zero(s))
        violate(TableInvariant::kEmptySlotNotZero, s, here, "count " + std::to_string(t.counts[s]));
      // What should be here still counts in the totals: a record placed on an empty slot lost its add.
      expected_total_count += base_count + here.size();
      for (int c = 0; c < 3; ++c) {
        placed_total[c] += fixed_base(c);
        for (std::uint32_t i : here) placed_total[c] += shared::ToFixedPoint(RecordOf(in, i).contribution[c], scale);
      }
      if (squares && fixed) {
        placed_square_total += evicted_by_policy ? 0 : fixed_square_before(s);
        for (std::uint32_t i : here)
          placed_square_total += shared::SquareToFixedPoint(glm::vec3(RecordOf(in, i).contribution), square_scale);
      }
      continue;
    }
    if (here.empty() && tag_before(s) == kEmptyTag)
      violate(TableInvariant::kOrphanTag, s, {}, "tag " + std::to_string(t.tags[s]));
    total_count += t.counts[s];
    const bool blended = in.temporal.blends() && base_count > seed.count && !here.empty();  // a seeded slot is new
    if (blended && !packed) {
      CheckBlend(in, s, here,
                 {fixed ? before->fixed_sums[s] : std::array<std::uint64_t, 3>{},
                  fixed ? std::array<float, 3>{} : before->float_sums[s], base_count - seed.count,
                  fixed_square_before(s), float_square_before(s)},
                 violations);
      if (squares && fixed) {
        table_square_total += t.fixed_squares[s];
        placed_square_total += t.fixed_squares[s];  // judged by the blend check, taken as it is
      }
      // The blend check is this slot's whole check: the totals take it as it is.
      expected_total_count += t.counts[s];
      continue;
    }
    if (packed) {
      // The exact words before the settle: any past 32 bits (24 for the count) wrapped on the device.
      std::array<unsigned __int128, 3> exact{};
      for (int c = 0; c < 3; ++c) {
        exact[c] = fixed_base(c);
        for (std::uint32_t i : here) exact[c] += shared::ToFixedPoint(RecordOf(in, i).contribution[c], scale);
      }
      const unsigned __int128 exact_count = (unsigned __int128)base_count + here.size();
      bool in_range = true;
      if (exact_count > shared::kPackedCountMask) {
        in_range = false;
        violate(TableInvariant::kCountMismatch, s, here,
                "count " + std::to_string(t.counts[s]) + ", exact " + Decimal(exact_count) +
                    ": more than packed-decimal's 24-bit count holds");
      }
      for (int c = 0; c < 3; ++c) {
        if (exact[c] <= 0xFFFFFFFFu) continue;
        in_range = false;
        violate(TableInvariant::kSumMismatch, s, here,
                "channel " + std::to_string(c) + ": sum " + std::to_string(t.fixed_sums[s][c]) + ", exact " +
                    Decimal(exact[c]) + ": the 32-bit sum wrapped");
      }
      const std::uint32_t frames_before = evicted_by_policy || !before ? 0u : before->frame_counters[s];
      glm::uvec4 accumulated{std::uint32_t(exact[0]), std::uint32_t(exact[1]), std::uint32_t(exact[2]),
                             shared::PackCountWord(std::uint32_t(exact_count), frames_before)};
      // Under a blending temporal mode the blend comes before the settle (core/temporal.h).
      if (blended && in_range) {
        accumulated = BlendPacked(in, s, here, {fixed_base(0), fixed_base(1), fixed_base(2)}, base_count, accumulated,
                                  violations);
      }
      const glm::uvec4 settled = shared::SettlePacked(accumulated);
      const std::array<std::uint64_t, 3> settled_sums = {settled.x, settled.y, settled.z};
      expected_total_count += shared::PackedCount(settled.w);
      for (int c = 0; c < 3; ++c) {
        table_total[c] += t.fixed_sums[s][c];
        placed_total[c] += settled_sums[c];
      }
      if (in_range && (t.counts[s] != shared::PackedCount(settled.w) || t.fixed_sums[s] != settled_sums ||
                       t.frame_counters[s] != shared::PackedFrames(settled.w))) {
        violate(TableInvariant::kPackedSettle, s, here,
                "count " + std::to_string(t.counts[s]) + ", sums " + SumsText(t.fixed_sums[s]) + ", frames " +
                    std::to_string(t.frame_counters[s]) + "; exact count " + Decimal(exact_count) + ", sums (" +
                    Decimal(exact[0]) + ", " + Decimal(exact[1]) + ", " + Decimal(exact[2]) + "), frames " +
                    std::to_string(frames_before) + (blended ? " blend and settle" : " settle") + " to count " +
                    std::to_string(shared::PackedCount(settled.w)) + ", sums " + SumsText(settled_sums) + ", frames " +
                    std::to_string(shared::PackedFrames(settled.w)));
      }
      continue;
    }
    const unsigned __int128 expected_count = (unsigned __int128)base_count + here.size();
    expected_total_count += expected_count;
    if (t.counts[s] != expected_count) {
      violate(TableInvariant::kCountMismatch, s, here,
              "count " + std::to_string(t.counts[s]) + (seed.count > 0 ? ", seeded " : ", before ") +
                  std::to_string(base_count) + " + placed " + std::to_string(here.size()) +
                  (expected_count >> 64 ? ": more than a 64-bit count holds (D12)" : ""));
    }
    if (squares) {
      unsigned __int128 exact = evicted_by_policy ? 0 : fixed_square_before(s);
      double exact_float = evicted_by_policy ? 0.0 : double(float_square_before(s)), magnitude = exact_float;
      for (std::uint32_t i : here) {
        const glm::vec3 contribution(RecordOf(in, i).contribution);
        exact += shared::SquareToFixedPoint(contribution, square_scale);
        exact_float += double(shared::SquareAsFloat(contribution));
        magnitude += double(shared::SquareAsFloat(contribution));
      }
      if (fixed) {
        table_square_total += t.fixed_squares[s];
        placed_square_total += exact;
        if (exact != t.fixed_squares[s]) {
          violate(TableInvariant::kSquareSumMismatch, s, here,
                  "square sum " + std::to_string(t.fixed_squares[s]) + ", exact " + Decimal(exact) +
                      (exact >> 64 ? ": the sum wrapped" : ""));
        }
      } else {
        const std::size_t terms = here.size() + (base_count > 0 ? 1 : 0);
        const double k = double(terms > 0 ? terms - 1 : 0), u = 0x1p-23;
        const double bound = k * u / (1.0 - k * u) * magnitude;
        if (!(std::abs(double(t.float_squares[s]) - exact_float) <= bound)) {
          violate(TableInvariant::kSquareSumMismatch, s, here,
                  "square sum " + std::to_string(t.float_squares[s]) + ", exact " + std::to_string(exact_float) +
                      ", bound " + std::to_string(bound));
        }
      }
    }
    for (int c = 0; c < 3; ++c) {
      unsigned __int128 exact = fixed_base(c);
      double exact_float = double(float_base(c)), magnitude = std::abs(exact_float);
      for (std::uint32_t i : here) {
        const float v = RecordOf(in, i).contribution[c];
        exact += shared::ToFixedPoint(v, scale);
        exact_float += double(v);
        magnitude += std::abs(double(v));
      }
      if (fixed) {
        table_total[c] += t.fixed_sums[s][c];
        placed_total[c] += exact;
        if (exact != t.fixed_sums[s][c]) {
          // An exact sum of 2^64 or more is one the table's 64 bits wrapped (a later frame brighter than the one
          // whose F the table keeps): said so, rather than printed modulo 2^64 beside an equal-looking sum.
          const std::uint64_t wraps = std::uint64_t(exact >> 64);
          violate(TableInvariant::kSumMismatch, s, here,
                  "channel " + std::to_string(c) + ": sum " + std::to_string(t.fixed_sums[s][c]) + ", exact " +
                      std::to_string(std::uint64_t(exact)) +
                      (wraps == 0 ? "" : " + " + std::to_string(wraps) + " x 2^64: the sum wrapped"));
        }
      } else {
        // Float atomics are not promised to round to nearest: u = 2^-23, gamma(k) = k u / (1 - k u), over the k
        // adds after the first term (the sum before the frame counts as one when there is one).
        const std::size_t terms = here.size() + (base_count > 0 ? 1 : 0);
        const double k = double(terms > 0 ? terms - 1 : 0), u = 0x1p-23;
        const double bound = k * u / (1.0 - k * u) * magnitude;
        if (!(std::abs(double(t.float_sums[s][c]) - exact_float) <= bound)) {
          violate(TableInvariant::kSumMismatch, s, here,
                  "channel " + std::to_string(c) + ": sum " + std::to_string(t.float_sums[s][c]) + ", exact " +
                      std::to_string(exact_float) + ", bound " + std::to_string(bound));
        }
      }
    }
  }
  if (t.levels > 1) CheckLevelNesting(in, touches, seeds, violations);
  if (total_count != expected_total_count) {
    violate(TableInvariant::kTotalMismatch, 0xFFFFFFFFu, {},
            "count " + Decimal(total_count) + ", expected " + Decimal(expected_total_count));
  }
  for (int c = 0; c < 3; ++c) {
    if (fixed && table_total[c] != placed_total[c]) {
      violate(TableInvariant::kTotalMismatch, 0xFFFFFFFFu, {}, "channel " + std::to_string(c) + " total differs");
    }
  }
  if (squares && fixed && table_square_total != placed_square_total) {
    violate(TableInvariant::kTotalMismatch, 0xFFFFFFFFu, {}, "square total differs");
  }
  return violations;
}

}  // namespace hpsf
