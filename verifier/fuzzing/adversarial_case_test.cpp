// The adversarial cases of hpsf fuzz: a pure function of (seed, run), always valid, every family drawn, and each
// family reaching what it is built for in nearly every case (else the fuzzer's power is luck).
#include "verifier/fuzzing/adversarial_case.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "core/cell_interpolation.h"
#include "core/footprint.h"
#include "core/input_check.h"
#include "core/shared/cell_interpolation.h"
#include "core/shared/key.h"
#include "reference/reference_filter.h"

namespace hpsf {
namespace {

std::vector<KeyResult> Keys(const AdversarialCase& c) {
  const shared::KeyParams params =
      MakeKeyParams(c.config, FootprintScale(c.config.filter_width_px, c.batch.fov_y_radians, c.batch.height),
                    std::uint32_t(c.batch.records.size()));
  std::vector<KeyResult> keys;
  for (const Record& r : c.batch.records) {
    keys.push_back(CheckRecordInputs(r) == InputVerdict::kAccepted ? shared::ComputeKey(params, r) : KeyResult{});
  }
  return keys;
}

using Words = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;
Words WordsOf(const KeyResult& k) {
  return {k.words.cell_x, k.words.cell_y, k.words.cell_z, k.words.level, k.words.normal};
}

// What the family is built to reach, read from the keys core computes for the case's records.
bool ReachesItsAim(const AdversarialCase& c) {
  const std::vector<KeyResult> keys = Keys(c);
  std::set<Words> distinct;
  switch (c.family) {
    case AdversarialFamily::kCrowded:  // neighbours share a cell
      for (std::size_t i = 1; i < keys.size(); ++i) {
        if (keys[i].status == shared::kKeyed && keys[i - 1].status == shared::kKeyed &&
            WordsOf(keys[i]) == WordsOf(keys[i - 1]))
          return true;
      }
      return false;
    case AdversarialFamily::kZeroFingerprint:  // a key whose reduced fingerprint is 0 before the fix
      for (const KeyResult& k : keys) {
        if (k.status == shared::kKeyed && (shared::FullFingerprint(k.words) >> (32u - c.config.fingerprint_bits)) == 0u)
          return true;
      }
      return false;
    case AdversarialFamily::kWrappingWindows:  // two distinct keys whose windows reach the last slot
      for (const KeyResult& k : keys) {
        if (k.status == shared::kKeyed && k.slot0 + c.config.probe_limit > c.config.capacity)
          distinct.insert(WordsOf(k));
      }
      return distinct.size() >= 2;
    case AdversarialFamily::kSharedFingerprint: {  // two distinct keys with one slot0 and one fingerprint
      std::map<std::pair<std::uint32_t, std::uint32_t>, std::set<Words>> by_slot_and_tag;
      for (const KeyResult& k : keys) {
        if (k.status == shared::kKeyed) by_slot_and_tag[{k.slot0, k.fingerprint}].insert(WordsOf(k));
      }
      for (const auto& [slot_and_tag, words] : by_slot_and_tag) {
        if (words.size() >= 2) return true;
      }
      return false;
    }
    case AdversarialFamily::kKeyPath:
      return true;                      // the property-test generators' own reach is generator_tests'
    case AdversarialFamily::kSpread: {  // a cell whose records sit in two workgroups of the Vulkan accumulate
      std::map<Words, std::set<std::size_t>> workgroups;
      for (std::size_t i = 0; i < keys.size(); ++i) {
        if (keys[i].status == shared::kKeyed) workgroups[WordsOf(keys[i])].insert(i / kAccumulateRecordsPerWorkgroup);
      }
      for (const auto& [words, groups] : workgroups) {
        if (groups.size() >= 2) return true;
      }
      return false;
    }
  }
  return false;
}

TEST(AdversarialCase, IsAPureFunctionOfSeedAndRun) {
  for (std::uint64_t run : {0ull, 1ull, 77ull, 1ull << 40}) {
    const AdversarialCase a = MakeAdversarialCase(5, run), b = MakeAdversarialCase(5, run);
    EXPECT_EQ(a.ToString(), b.ToString());
    ASSERT_EQ(a.batch.records.size(), b.batch.records.size());
    EXPECT_EQ(std::memcmp(a.batch.records.data(), b.batch.records.data(), a.batch.records.size() * sizeof(Record)), 0);
  }
  EXPECT_NE(MakeAdversarialCase(5, 0).ToString(), MakeAdversarialCase(6, 0).ToString());
}

TEST(AdversarialCase, EveryCaseIsValidAndEveryFamilyIsDrawn) {
  std::array<int, kAdversarialFamilies> families{};
  std::array<int, 4> spoiled{};  // rejected inputs, unkeyable records, records without a vertex, float32 tables
  int sequences = 0, small_f = 0, packed = 0, bright = 0;
  std::set<std::string> policies, temporals;
  for (std::uint64_t run = 0; run < 2000; ++run) {
    const AdversarialCase c = MakeAdversarialCase(1, run);
    ++families[std::size_t(c.family)];
    EXPECT_NO_THROW(c.config.Validate());
    EXPECT_NO_THROW(c.emulator.Validate());
    ASSERT_EQ(std::size_t(c.batch.width) * c.batch.height * c.batch.samples_per_pixel, c.batch.records.size());
    if (c.family == AdversarialFamily::kSpread) {  // over 2 to 4 workgroups
      ASSERT_GT(c.batch.records.size(), kAccumulateRecordsPerWorkgroup);
      ASSERT_LE(c.batch.records.size(), 4 * kAccumulateRecordsPerWorkgroup);
    } else {
      ASSERT_GE(c.batch.records.size(), 2u);
      ASSERT_LE(c.batch.records.size(), 96u);
    }
    // A sequence: 2 to 6 frames numbered 1, 2, ... after the first, each a valid batch, F room for all of them.
    EXPECT_EQ(c.config.frames, c.later.size() + 1);
    ASSERT_LE(c.later.size(), 5u);
    for (std::size_t k = 0; k < c.later.size(); ++k) {
      EXPECT_EQ(c.later[k].frame, k + 1);
      ASSERT_GE(c.later[k].records.size(), 1u);
      ASSERT_EQ(std::size_t(c.later[k].width) * c.later[k].height * c.later[k].samples_per_pixel,
                c.later[k].records.size());
    }
    sequences += !c.later.empty();
    if (!c.later.empty()) {
      policies.insert(c.config.eviction.ToString());
      temporals.insert(c.config.temporal.ToString());
    }
    if (c.config.fixed_point_bits) {
      small_f += 1;
      EXPECT_GE(*c.config.fixed_point_bits, -2);
      EXPECT_LE(*c.config.fixed_point_bits, 9);
    }
    const std::vector<KeyResult> keys = Keys(c);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const InputVerdict verdict = CheckRecordInputs(c.batch.records[i]);
      spoiled[0] += verdict != InputVerdict::kAccepted;
      spoiled[1] += verdict == InputVerdict::kAccepted && keys[i].status == shared::kKeyUnkeyable;
      spoiled[2] += !shared::RecordHasVertex(c.batch.records[i]);
    }
    spoiled[3] += c.config.accumulation == Accumulation::kFloat32;
    packed += c.config.accumulation == Accumulation::kPackedDecimal;
    // A bright packed-decimal case (Contribution() draws below 4): a sequence, no word of it able to wrap.
    float brightest = 0.0f;
    for (const RecordBatch& frame : c.Frames()) {
      for (const Record& r : frame.records) {
        if (CheckRecordInputs(r) != InputVerdict::kAccepted || !shared::RecordHasVertex(r)) continue;  // adds nothing
        for (int ch = 0; ch < 3; ++ch) brightest = std::max(brightest, r.contribution[ch]);
      }
    }
    if (c.config.accumulation == Accumulation::kPackedDecimal && brightest > 4.0f) {
      ++bright;
      EXPECT_FALSE(c.later.empty()) << c.ToString();
      std::size_t most = 0;
      for (const RecordBatch& frame : c.Frames()) most = std::max(most, frame.records.size());
      const double bound = c.config.temporal.blends() ? 0x1p30 : 0x1p31;
      EXPECT_LT(double(most) * double(brightest) * 1000.0, bound) << c.ToString();
    }
  }
  // 333 expected per family; a binomial's standard deviation is 17.
  for (int f = 0; f < kAdversarialFamilies; ++f) {
    EXPECT_GT(families[std::size_t(f)], 250) << ToString(AdversarialFamily(f));
    EXPECT_LT(families[std::size_t(f)], 420) << ToString(AdversarialFamily(f));
  }
  // One case in four a sequence, and the bright half of the packed-decimal cases that were not (1/4 + 1/6 x 1/2 x
  // 3/4 = 0.3125: 625 expected, sd 21), one fixed64 case in four a small F (375 before the packed-decimal draw takes
  // a sixth of the cases: 312, sd 16), every policy and temporal mode drawn.
  EXPECT_GT(sequences, 540);
  EXPECT_LT(sequences, 710);
  EXPECT_GT(small_f, 250);
  EXPECT_LT(small_f, 380);
  // One case in six packed-decimal sums: 333 expected, sd 17; half of those bright, 167 expected, sd 12 (given 333).
  EXPECT_GT(packed, 250);
  EXPECT_LT(packed, 420);
  EXPECT_GT(bright, 115);
  EXPECT_LT(bright, 220);
  EXPECT_EQ(policies, (std::set<std::string>{"none", "priority", "stale:1", "stale:2", "stale:3", "strict"}));
  EXPECT_EQ(temporals.size(), 5u);  // adaptive-variance among the cases with second moments
  for (int kind = 0; kind < 4; ++kind) EXPECT_GT(spoiled[std::size_t(kind)], 100) << "kind " << kind;
}

// A user's shader handles one mode: with --accum given, every case of every family is in it (the key-path family
// once replaced the whole configuration, and ran fixed64 cases against a float32 shader).
TEST(AdversarialCase, AGivenModeHoldsInEveryFamily) {
  for (const Accumulation mode : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    std::set<int> families;
    for (std::uint64_t run = 0; run < 300; ++run) {
      const AdversarialCase c = MakeAdversarialCase(4, run, {96, true, mode, true});
      families.insert(int(c.family));
      ASSERT_EQ(c.config.accumulation, mode) << c.ToString();
    }
    EXPECT_EQ(families.size(), std::size_t(kAdversarialFamilies));
  }
}

// A quarter of the cases add their records at 2 or 3 levels (core/shared/levels.h) with a threshold of 1 to 4, with
// compaction and priority eviction among them; none where the options say the kernels do not know the levels.
TEST(AdversarialCase, SeveralLevelsAreDrawnWhereTheKernelsKnowThem) {
  int with_levels = 0, with_compaction = 0, with_priority = 0;
  std::set<std::uint32_t> thresholds;
  constexpr int kRuns = 3000;
  for (std::uint64_t run = 0; run < kRuns; ++run) {
    const AdversarialCase c = MakeAdversarialCase(6, run);
    if (c.config.levels == 1) continue;
    ++with_levels;
    with_compaction += c.config.compaction != Compaction::kNone;
    thresholds.insert(c.config.min_count);
    with_priority += c.config.eviction.by_priority();
    EXPECT_LE(c.config.levels, 3u);
  }
  EXPECT_GT(with_levels, kRuns / 6);
  EXPECT_LT(with_levels, kRuns / 3);
  EXPECT_GT(with_compaction, 0);
  EXPECT_GT(with_priority, 0);
  EXPECT_EQ(thresholds, (std::set<std::uint32_t>{1, 2, 3, 4}));
  AdversarialOptions none;
  none.levels = false;
  for (std::uint64_t run = 0; run < 200; ++run) EXPECT_EQ(MakeAdversarialCase(6, run, none).config.levels, 1u);
}

// Several filtered bounces in half the sequences not in packed-decimal: every frame carries one scattered vertex per
// record, a record of its own frame with a weight below 1/2 (or no vertex), and the reference finds the cells of the
// frame before for some of them, so the fuzzed backend's transport is judged; none where the options say the backend
// does not transport.
TEST(AdversarialCase, SequencesTransportLightBetweenFrames) {
  int transporting = 0, sequences = 0;
  std::uint64_t found = 0;
  constexpr int kRuns = 2000;
  for (std::uint64_t run = 0; run < kRuns; ++run) {
    const AdversarialCase c = MakeAdversarialCase(7, run);
    sequences += !c.later.empty() && c.config.accumulation != Accumulation::kPackedDecimal;
    if (!c.config.transport) continue;
    ++transporting;
    ASSERT_FALSE(c.later.empty());
    for (const RecordBatch& frame : c.Frames()) {
      ASSERT_EQ(frame.scattered.size(), frame.records.size());
      for (const Record& s : frame.scattered) {
        for (int k = 0; k < 3; ++k) EXPECT_LT(s.throughput[k], 0.5f);
      }
    }
    if (transporting <= 40) {
      std::optional<FilterResult> previous;
      FilterConfig config = c.config;
      for (const RecordBatch& frame : c.Frames()) {
        config.frame = frame.frame;
        previous = ReferenceFilter(frame, config, previous ? &*previous : nullptr);
        found += previous->stats.transport.found;
      }
    }
  }
  EXPECT_GT(transporting, sequences / 3);
  EXPECT_LT(transporting, 2 * sequences / 3);
  EXPECT_GT(found, 0u);
  AdversarialOptions none;
  none.transport = false;
  for (std::uint64_t run = 0; run < 200; ++run) EXPECT_FALSE(MakeAdversarialCase(7, run, none).config.transport);
}

// Level seeding (--level-change seed) in some of the sequences keyed with level of detail, whose later frames see
// records from twice or half as far: in most of those the reference seeds a cell from the frame before, so the
// fuzzed backend's seeding is judged; in none where the options say the kernels do not seed.
TEST(AdversarialCase, ResolutionChangesSeedCellsAcrossLevels) {
  int with_seed = 0, seeding = 0, relevelled = 0;
  std::uint64_t cells = 0;
  for (std::uint64_t run = 0; run < 3000; ++run) {
    const AdversarialCase c = MakeAdversarialCase(8, run);
    if (!c.config.level_seed.enabled) continue;
    ++with_seed;
    EXPECT_TRUE(c.config.lod);
    EXPECT_FALSE(c.later.empty());
    // A record of the first frame seen again from another distance keys another level.
    const shared::KeyParams params =
        MakeKeyParams(c.config, FootprintScale(c.config.filter_width_px, c.batch.fov_y_radians, c.batch.height), 1);
    bool moved = false;
    for (const Record& first : c.batch.records) {
      for (const RecordBatch& frame : c.later) {
        for (const Record& again : frame.records) {
          if (again.position.x != first.position.x || again.position.y != first.position.y ||
              again.position.z != first.position.z || CheckRecordInputs(again) != InputVerdict::kAccepted ||
              CheckRecordInputs(first) != InputVerdict::kAccepted) {
            continue;
          }
          moved =
              moved || shared::ComputeKey(params, again).words.level != shared::ComputeKey(params, first).words.level;
        }
      }
    }
    relevelled += moved;
    std::optional<FilterResult> result;
    std::uint64_t seeded = 0;
    for (const RecordBatch& frame : c.Frames()) {
      FilterConfig config = c.config;
      config.frame = frame.frame;
      result = ReferenceFilter(frame, config, result ? &*result : nullptr);
      seeded += result->stats.cells_seeded;
    }
    seeding += seeded > 0;
    cells += seeded;
  }
  std::printf(
      "level seeding in %d of 3000 cases; a record keys another level in a later frame in %d; the reference "
      "seeded %llu cells, in %d of them\n",
      with_seed, relevelled, static_cast<unsigned long long>(cells), seeding);
  EXPECT_GT(with_seed, 10);
  EXPECT_GT(relevelled, with_seed * 3 / 4);
  EXPECT_GT(seeding, with_seed / 2);
  AdversarialOptions none;
  none.level_change = false;
  for (std::uint64_t run = 0; run < 3000; ++run)
    EXPECT_FALSE(MakeAdversarialCase(8, run, none).config.level_seed.enabled);
}

// A quarter of the cases of the families whose aim is not a fingerprint's store full keys, and half of the crowded
// ones among them put two distinct cells whose keys share their low word (a column) into a table.
TEST(AdversarialCase, FullKeysAreDrawnAndAColumnSharesTheLowWord) {
  int full = 0, eligible = 0, columns = 0, crowded = 0;
  for (std::uint64_t run = 0; run < 2000; ++run) {
    const AdversarialCase c = MakeAdversarialCase(2, run);
    const bool fingerprint_aim = c.family == AdversarialFamily::kZeroFingerprint ||
                                 c.family == AdversarialFamily::kSharedFingerprint ||
                                 c.family == AdversarialFamily::kWrappingWindows;
    if (c.config.key_identity == KeyIdentity::kFull) {
      ASSERT_FALSE(fingerprint_aim) << c.ToString();
      ++full;
    }
    eligible += !fingerprint_aim;
    if (c.config.key_identity != KeyIdentity::kFull || c.family != AdversarialFamily::kCrowded) continue;
    ++crowded;
    std::map<std::uint32_t, std::set<Words>> by_low_word;
    for (const KeyResult& k : Keys(c)) {
      if (k.status == shared::kKeyed) by_low_word[k.fingerprint].insert(WordsOf(k));
    }
    columns += std::any_of(by_low_word.begin(), by_low_word.end(), [](const auto& w) { return w.second.size() >= 2; });
  }
  std::printf("full keys in %d of %d cases that may have them; a shared low word in %d of %d crowded ones\n", full,
              eligible, columns, crowded);
  EXPECT_GT(full, eligible / 5);
  EXPECT_LT(full, eligible / 3);
  EXPECT_GT(columns, crowded / 3);
}

TEST(AdversarialCase, EachFamilyReachesItsAim) {
  std::array<int, kAdversarialFamilies> drawn{}, reached{};
  for (std::uint64_t run = 0; run < 2000; ++run) {
    const AdversarialCase c = MakeAdversarialCase(2, run);
    if (c.family == AdversarialFamily::kCrowded && c.batch.records.size() < 16) continue;  // few records may not repeat
    ++drawn[std::size_t(c.family)];
    reached[std::size_t(c.family)] += ReachesItsAim(c);
  }
  for (int f = 0; f < kAdversarialFamilies; ++f) {
    std::printf("%-18s reached its aim in %d of %d cases\n", ToString(AdversarialFamily(f)), reached[std::size_t(f)],
                drawn[std::size_t(f)]);
    EXPECT_GE(reached[std::size_t(f)], drawn[std::size_t(f)] * 9 / 10) << ToString(AdversarialFamily(f));
  }
}

// Second moments in about a quarter of the cases that can keep them, never with packed-decimal sums or level seeding
// (which refuse them), and in none where the options say the passes do not keep the squares.
TEST(AdversarialCase, SomeCasesKeepSecondMoments) {
  int keeping = 0;
  for (std::uint64_t run = 0; run < 800; ++run) {
    const AdversarialCase c = MakeAdversarialCase(9, run);
    if (!c.config.second_moments) continue;
    ++keeping;
    EXPECT_NE(c.config.accumulation, Accumulation::kPackedDecimal);
    EXPECT_FALSE(c.config.level_seed.enabled);
  }
  EXPECT_GT(keeping, 100);
  EXPECT_LT(keeping, 250);
  AdversarialOptions none;
  none.second_moments = false;
  for (std::uint64_t run = 0; run < 200; ++run) EXPECT_FALSE(MakeAdversarialCase(9, run, none).config.second_moments);
}

// Half the cases that keep second moments interpolate (never with the search), by rules of both kinds that
// validate, and half of those blend own lights of their own (one per record of every frame, each channel in [0, 2]);
// none where the options say a team's resolve runs.
TEST(AdversarialCase, SomeCasesInterpolate) {
  int keeping = 0, interpolating = 0, step = 0, own = 0;
  for (std::uint64_t run = 0; run < 800; ++run) {
    const AdversarialCase c = MakeAdversarialCase(9, run);
    keeping += c.config.second_moments;
    if (!c.config.interpolation.enabled()) continue;
    ++interpolating;
    step += c.config.interpolation.function == shared::kInterpolationStep;
    EXPECT_TRUE(c.config.second_moments);
    EXPECT_FALSE(c.config.neighbour_search);
    EXPECT_EQ(ParseInterpolation(c.config.interpolation.ToString()), c.config.interpolation);
    if (c.batch.own_light.empty()) continue;
    ++own;
    std::vector<const RecordBatch*> frames = {&c.batch};
    for (const RecordBatch& frame : c.later) frames.push_back(&frame);
    for (const RecordBatch* frame : frames) {
      ASSERT_EQ(frame->own_light.size(), frame->records.size());
      for (std::size_t i = 0; i < frame->records.size(); ++i) {
        const glm::vec4 light = frame->own_light[i];
        EXPECT_EQ(light.w, 0.0f);
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(light[k], 0.0f);
          EXPECT_LE(light[k], 2.0f);
        }
      }
    }
  }
  std::printf("%d of %d cases keeping second moments interpolate, %d by steps, %d with own lights\n", interpolating,
              keeping, step, own);
  EXPECT_GT(own, interpolating / 4);
  EXPECT_LT(own, interpolating);
  EXPECT_GT(interpolating, keeping / 4);
  EXPECT_GT(step, 0);
  EXPECT_LT(step, interpolating);
  AdversarialOptions none;
  none.interpolation = false;
  for (std::uint64_t run = 0; run < 200; ++run) {
    EXPECT_FALSE(MakeAdversarialCase(9, run, none).config.interpolation.enabled());
  }
}

}  // namespace
}  // namespace hpsf
