#include "verifier/contract/capture_judgement.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <tuple>

#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "core/footprint.h"
#include "core/hashed_run.h"
#include "core/input_check.h"
#include "core/key_batch.h"
#include "core/shared/fixed_point.h"
#include "verifier/checker/classified_slots.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/given_keys.h"
#include "verifier/contract/rerun_check.h"

namespace hpsf {
namespace {

// The capture against its declaration: what the buffers' shape says must be what the declaration declares.
void CheckAgainstDeclaration(const Capture& c, const FilterConfig& config) {
  auto fail = [&](const std::string& problem) { throw InputError(c.path + ": " + problem); };
  if (c.capacity != config.capacity) {
    fail("the table has " + std::to_string(c.capacity) + " slots, its declaration " + std::to_string(config.capacity));
  }
  const Accumulation captured = c.float32_sums  ? Accumulation::kFloat32
                                : c.packed_sums ? Accumulation::kPackedDecimal
                                                : Accumulation::kFixed64;
  if (captured != config.accumulation) {
    fail("the sums are " + ToString(captured) + ", its declaration's " + ToString(config.accumulation));
  }
  if (c.last_seen != config.eviction.enabled()) {
    fail(config.eviction.enabled() ? "its declaration evicts, but the tables carry no last-seen frames"
                                   : "the tables carry last-seen frames, but its declaration does not evict");
  }
  if (captured == Accumulation::kFixed64 &&
      (c.fixed_point_bits < shared::kFixedPointBitsMin || c.fixed_point_bits > shared::kFixedPointBitsMax)) {
    fail("F " + std::to_string(c.fixed_point_bits) + " is outside [-126, 126]");
  }
  if (c.full_keys != (config.key_identity == KeyIdentity::kFull)) {
    fail(c.full_keys ? "the identities and tags are 64-bit full keys, but its declaration stores fingerprints"
                     : "its declaration stores full keys (key.identity full), but the identities and tags are 32-bit");
  }
  if (config.level_seed.enabled) fail("level seeding (passes.level_change) is not judged from a capture");
  const bool compacting = config.compaction == Compaction::kOccupiedList;
  if (compacting != c.occupied.has_value()) {
    fail(compacting ? "its declaration compacts (passes.compaction occupied-list), but the capture holds no OCCL list"
                    : "the capture holds an occupied list (OCCL), but its declaration does not compact");
  }
  if (c.hpsf_records && c.key_words != 6) {
    fail("hpsf's records come with hpsf's key, of 6 words; the capture's keys have " + std::to_string(c.key_words));
  }
}

HashTableDump TableOf(const CapturedTable& t, const Capture& c, const FilterConfig& config, int fixed_point_bits) {
  HashTableDump d;
  d.capacity = c.capacity;
  d.probe_limit = config.probe_limit;
  d.probing = config.probing;
  d.fingerprint_bits = config.fingerprint_bits;
  d.key_identity = config.key_identity;
  d.accumulation = config.accumulation;
  d.fixed_point_bits = fixed_point_bits;
  d.tags = t.tags;
  d.fixed_sums = t.fixed_sums;
  d.float_sums = t.float_sums;
  d.counts = t.counts;
  d.last_seen = t.last_seen;
  d.frame_counters = t.frame_counters;
  return d;
}

// The records the checker sums: hpsf's own when captured, else each one's contribution, with a vertex where it has
// a key (a non-finite or negative contribution is then rejected, as hpsf rejects such a record).
std::vector<Record> RecordsToCheck(const Capture& c) {
  if (c.hpsf_records) return c.hpsf_records->records;
  std::vector<Record> records(c.record_count());
  for (std::size_t i = 0; i < records.size(); ++i) {
    Record& r = records[i];
    r = {};
    r.contribution = glm::vec4(c.contributions[i][0], c.contributions[i][1], c.contributions[i][2], 0.0f);
    r.path.z = c.statuses[i] == shared::kKeyNoVertex ? 0u : shared::kRecordHasVertex;
  }
  return records;
}

// Level 1: the given keys' own checks, then with hpsf's records every key word against core's.
std::uint64_t JudgeKeys(const Capture& c, const FilterConfig& config, std::span<const Record> records,
                        std::vector<KeyResult>& keys, LevelVerdict& verdict) {
  const std::uint64_t judged = JudgeGivenKeys(keys, records, c.capacity, config, "", verdict);
  if (!c.hpsf_records) return judged;
  // hpsf's key: every word of every accepted record against core's, whose level then stands for the captured one.
  const CapturedRecords& r = *c.hpsf_records;
  KeyParams params;
  try {  // the camera is the capture's: a field of view or height no camera has is its bad input
    params = MakeKeyParams(config, FootprintScale(config.filter_width_px, r.fov_y_radians, r.height),
                           std::uint32_t(records.size()));
  } catch (const ConfigError& e) {
    throw InputError(c.path + ": RECD's camera: " + e.what());
  }
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (CheckRecordInputs(records[i]) != InputVerdict::kAccepted) continue;
    const KeyResult expected = shared::ComputeKey(params, records[i]);
    const auto want = KeyResultWords(expected);
    KeyResult got = keys[i];
    got.level = expected.level;  // a capture carries no level: hpsf's is core's
    const auto have = KeyResultWords(got);
    for (int w = 0; w < int(want.size()); ++w) {
      if (want[w] != have[w]) {
        verdict.Fail("record " + std::to_string(i) + ": " + KeyResultWordName(w) + " differs (core " +
                     std::to_string(want[w]) + ", capture " + std::to_string(have[w]) + ")");
        break;
      }
    }
    keys[i].level = expected.level;
    if (!std::equal(
            c.contributions[i].begin(), c.contributions[i].end(), &records[i].contribution[0],
            [](float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); })) {
      verdict.Fail("record " + std::to_string(i) + ": the captured contribution is not its record's");
    }
  }
  return judged;
}

template <typename T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Whether two tables hold the same cells: the same (tag, count, sums, last-seen) in their occupied slots, whichever
// slots those are (an unordered run may place a cell's first record in either of two racing slots).
bool SameCells(const CapturedTable& a, const CapturedTable& b) {
  using Cell = std::tuple<std::uint64_t, std::uint64_t, std::array<std::uint64_t, 3>, std::array<std::uint32_t, 3>,
                          std::uint32_t>;
  const auto cells = [](const CapturedTable& t) {
    std::vector<Cell> out;
    for (std::size_t s = 0; s < t.tags.size(); ++s) {
      if (t.tags[s] == 0) continue;
      std::array<std::uint32_t, 3> float_bits{};
      if (!t.float_sums.empty()) float_bits = std::bit_cast<std::array<std::uint32_t, 3>>(t.float_sums[s]);
      out.emplace_back(t.tags[s], t.counts[s], t.fixed_sums.empty() ? std::array<std::uint64_t, 3>{} : t.fixed_sums[s],
                       float_bits, t.last_seen.empty() ? 0u : t.last_seen[s]);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  return cells(a) == cells(b);
}

// A rerun judges determinism only of the same inputs: the first of them that differs, or "".
std::string InputDifference(const Capture& a, const Capture& b) {
  if (a.declaration != b.declaration) return "its declaration differs";
  if (a.frame != b.frame) return "it is frame " + std::to_string(b.frame) + ", not " + std::to_string(a.frame);
  if (a.capacity != b.capacity || a.key_words != b.key_words || a.float32_sums != b.float32_sums ||
      a.last_seen != b.last_seen || (!a.float32_sums && a.fixed_point_bits != b.fixed_point_bits)) {
    return "its frame header differs (capacity, key words, sums, F or last-seen frames)";
  }
  if (a.record_count() != b.record_count()) {
    return "it holds " + std::to_string(b.record_count()) + " records, not " + std::to_string(a.record_count());
  }
  for (std::size_t i = 0; i < a.record_count(); ++i) {
    const bool same = std::memcmp(&a.contributions[i], &b.contributions[i], sizeof a.contributions[i]) == 0 &&
                      std::equal(a.keys.begin() + std::ptrdiff_t(i * a.key_words),
                                 a.keys.begin() + std::ptrdiff_t((i + 1) * a.key_words),
                                 b.keys.begin() + std::ptrdiff_t(i * a.key_words)) &&
                      a.home_slots[i] == b.home_slots[i] && a.identities[i] == b.identities[i] &&
                      a.statuses[i] == b.statuses[i];
    if (!same) return "record " + std::to_string(i) + "'s contribution, key, home slot, identity or status differs";
  }
  if (a.hpsf_records.has_value() != b.hpsf_records.has_value() ||
      (a.hpsf_records && !SameBytes(a.hpsf_records->records, b.hpsf_records->records))) {
    return "its hpsf records differ";
  }
  if (a.before.has_value() != b.before.has_value() || (a.before && !SameCells(*a.before, *b.before))) {
    return "its table before the frame holds other cells";
  }
  return "";
}

}  // namespace

std::vector<KeyResult> CapturedKeys(const Capture& c) {
  std::vector<KeyResult> keys(c.record_count());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    std::uint32_t w[6] = {};
    for (std::uint32_t k = 0; k < c.key_words; ++k) w[k] = c.keys[i * c.key_words + k];
    KeyResult& key = keys[i];
    key = shared::EmptyKeyResult(c.statuses[i]);
    key.words = {w[0], w[1], w[2], w[3], w[4], w[5]};
    key.slot0 = c.home_slots[i];
    key.fingerprint = std::uint32_t(c.identities[i]);
    key.identity_high = std::uint32_t(c.identities[i] >> 32);
  }
  return keys;
}

CrosscheckReport JudgeCapture(const Capture& capture, FilterConfig config, const Capture* rerun) {
  CheckAgainstDeclaration(capture, config);
  if (rerun) {
    if (const std::string difference = InputDifference(capture, *rerun); !difference.empty()) {
      throw InputError(rerun->path + ": not a rerun of " + capture.path + ": " + difference);
    }
  }
  config.frame = capture.frame;
  const std::vector<Record> records = RecordsToCheck(capture);
  // float32 sums: the F hpsf's range check assumes for the batch (the checker's exact sums use it), which float32
  // refuses below kFloat32FixedPointBitsMin, as every backend does.
  // packed-decimal sums are at 1000 whatever F the capture carries (core/accumulation.h).
  const int fixed_point_bits = capture.float32_sums  ? ChooseFixedPointBits(records)
                               : capture.packed_sums ? 0
                                                     : capture.fixed_point_bits;
  try {
    if (capture.float32_sums) {
      RequireFloat32Range(fixed_point_bits);
    } else if (capture.packed_sums) {
      RequirePackedDecimalConverts(records);
    } else {
      RequireFixedPointConverts(records, fixed_point_bits);
    }
  } catch (const ConfigError& e) {
    throw InputError(capture.path + ": " + e.what());
  }
  LevelVerdict keys{1, "keys", true, true, "", {}};
  LevelVerdict tables{2, "tables", true, true, "", {}};
  LevelVerdict ideal{3, "agreement with the reference", true, true, "", {}};
  LevelVerdict determinism{4, "determinism", false, true, "one capture is one run", {}};

  HashedRun run;
  run.keys = CapturedKeys(capture);
  const std::uint64_t judged = JudgeKeys(capture, config, records, run.keys, keys);
  // A record of hpsf's without a vertex has no key, whatever status the capture gives it (level 1 names that): the
  // checker and the exact map must not sum its contribution, which hpsf never checked.
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (!shared::RecordHasVertex(records[i])) run.keys[i].status = shared::kKeyNoVertex;
  }
  keys.note = std::to_string(judged) + " keyed records: home slot, identity, one key per cell" +
              (capture.hpsf_records ? "; hpsf's key: every word against core's" : "");

  run.table = TableOf(capture.after, capture, config, fixed_point_bits);
  if (capture.occupied) {
    run.table.compacted = true;
    run.table.occupied = *capture.occupied;
  }
  run.placements = capture.placements;
  std::optional<HashTableDump> before;
  if (capture.before) before = TableOf(*capture.before, capture, config, fixed_point_bits);
  // A team's list the frame's passes started from: held to the table before the frame, as the list after is to the
  // table after (a slot it missed was neither settled, blended nor evicted by a pass over the list).
  if (before && capture.occupied_before) {
    before->compacted = true;
    before->occupied = *capture.occupied_before;
    for (const TableViolation& v : CheckOccupiedListOf(*before))
      tables.Fail("capture, before the frame: " + v.ToString());
  }
  TableCheckInput input{run.table, records, run.keys, run.placements};
  input.before = before ? &*before : nullptr;
  input.eviction = config.eviction;
  input.frame = config.frame;
  input.temporal = config.temporal;
  input.normal_in_index = config.normal_in_index;
  for (const TableViolation& v : CheckTable(input)) tables.Fail("capture: " + v.ToString());
  tables.note = std::string("table checker") + (before ? ", from the captured table before the frame" : "") +
                (capture.occupied_before ? ", its occupied list held to it" : "");

  ClassifiedSlots classes(config.eviction.by_priority(), false, config.normal_in_index);
  const std::vector<bool>& classified = classes.AddFrame(run);
  CountProbes(run);
  const std::uint64_t compared =
      CompareWithExactMap(records, run, before ? &*before : nullptr, classified, config, "", ideal);
  ideal.note = std::string("the exact map over the captured key words: one slot per cell; ") +
               (capture.float32_sums ? "counts" : "counts and exact sums") +
               " of the frame equal to each cell's outside the classified slots; " + std::to_string(compared) +
               " records compared; no image in a capture";

  if (rerun) {
    // The rerun's run as the judge sees the capture's: its keys are the capture's (the inputs are the same).
    HashedRun again;
    again.keys = run.keys;
    again.table = TableOf(rerun->after, *rerun, config, fixed_point_bits);
    again.placements = rerun->placements;
    ClassifiedSlots rerun_classes(config.eviction.by_priority(), false, config.normal_in_index);
    rerun_classes.AddFrame(again);
    CountProbes(again);
    const bool failed_or_aliased =
        run.probe_failures + again.probe_failures + classes.aliased_slots() + rerun_classes.aliased_slots() > 0;
    const RerunPromise promise = RerunPromiseFor(false, config.accumulation, failed_or_aliased);
    determinism = {4,
                   "determinism",
                   true,
                   true,
                   "against the rerun " + rerun->path + "; promised: " + ToString(promise) + " (no image in a capture)",
                   {}};
    for (const std::string& difference : CompareReruns(run, again, promise)) determinism.Fail(difference);
  }

  CrosscheckReport report;
  report.levels = {keys, tables, ideal, determinism};
  report.quality.push_back({"capture", run.probe_failures, classes.aliased_slots(), classes.classified_records()});
  report.fixed_point_bits = fixed_point_bits;
  report.accumulation = config.accumulation;
  return report;
}

}  // namespace hpsf
