// Captures judged offline (`hpsf judge`, verifier/contract/capture_judgement.h):
// - a frame of hpsf's own host, written through the header a team's engine calls, gets from the judge the verdict
//   the host gave it, level by level, for the clean table and for every broken kernel or shader the host's frame
//   can be captured from;
// - a team's own cache, with keys hpsf has never seen (two words, its own hashes, aligned buckets), is judged from
//   its buffers alone: its clean table passes, crowded or roomy, and each bug production caches shipped is named
//   at the level that owns it.

#include "verifier/contract/capture_judgement.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/capture_file.h"
#include "core/capture_writer.h"
#include "core/error.h"
#include "core/shared/fixed_point.h"
#include "core/shared/hash.h"
#include "emulated/defect_injection.h"
#include "property_tests/traced_batch.h"
#include "verifier/contract/crosscheck.h"
#include "verifier/contract/run_capture.h"
#include "verifier/gate/table_declaration.h"
#include "verifier/theory/table_statistics.h"

namespace hpsf::testing {
namespace {

// Levels 1 to 3 that failed (level 4 is a rerun's, which no capture holds).
std::set<int> FailedLevels(const CrosscheckReport& report) {
  std::set<int> failed;
  for (const LevelVerdict& v : report.levels) {
    if (v.level <= 3 && v.applicable && !v.passed) failed.insert(v.level);
  }
  return failed;
}

CrosscheckReport Judged(const std::string& path) {
  const Capture capture = ReadCapture(path);
  FilterConfig config;
  ApplyTableDeclarationText(capture.declaration, path, config);
  return JudgeCapture(capture, config);
}

std::string CaptureDir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/captures-" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

struct HostCase {
  std::string name;
  Defect defect = Defect::kNone;
  FilterConfig config;
  std::uint32_t frames = 1;
  double spurious_cas = 0.0;
  bool host_fails = false;  // the defect shows in these frames (else the comparison would be of two passes only)
};

FilterConfig Crowded() {
  FilterConfig config;
  config.capacity = 256;
  config.fingerprint_bits = 8;
  return config;
}

FilterConfig Roomy() {
  FilterConfig config;
  config.capacity = 1u << 12;
  return config;
}

std::vector<HostCase> EmulatorCases() {
  std::vector<HostCase> cases;
  cases.push_back({"clean roomy", Defect::kNone, Roomy()});
  cases.push_back({"clean crowded", Defect::kNone, Crowded()});
  FilterConfig buckets = Crowded();
  buckets.probing = ProbeKind::kBucket;
  buckets.probe_limit = 4;
  cases.push_back({"clean crowded bucket:4", Defect::kNone, buckets});
  FilterConfig evicting = Crowded();
  evicting.eviction = ParseEviction("stale:1");
  evicting.temporal = ParseTemporal("ema:0.8");
  cases.push_back({"clean crowded stale:1 ema, 3 frames", Defect::kNone, evicting, 3});
  FilterConfig listed = evicting;
  listed.compaction = Compaction::kOccupiedList;
  cases.push_back({"clean crowded stale:1 ema, occupied list, 3 frames", Defect::kNone, listed, 3});
  FilterConfig priority = Crowded();
  priority.eviction = ParseEviction("priority");
  cases.push_back({"clean crowded priority, 3 frames", Defect::kNone, priority, 3});
  FilterConfig float32 = Crowded();
  float32.accumulation = Accumulation::kFloat32;
  cases.push_back({"clean crowded float32, 2 frames", Defect::kNone, float32, 2});
  cases.push_back({"D2", Defect::kD2AddsAgain, Crowded(), 1, 0.0, true});
  cases.push_back({"D3", Defect::kD3ZeroFingerprint, Crowded(), 1, 0.0, true});
  cases.push_back({"D9", Defect::kD9NonAtomicAdd, Roomy(), 1, 0.0, true});
  FilterConfig coarse = Roomy();
  coarse.fixed_point_bits = 4;
  cases.push_back({"D11", Defect::kD11TruncatedFixedPoint, coarse, 1, 0.0, true});
  cases.push_back({"D13", Defect::kD13LoadThenStoreClaim, Roomy(), 1, 0.0, true});
  cases.push_back({"count-store-claim-first", Defect::kCountStoreClaimFirst, Roomy(), 1, 0.0, true});
  FilterConfig stale = Roomy();
  stale.eviction = ParseEviction("strict");
  cases.push_back({"last-seen-claimer-only, 3 frames", Defect::kLastSeenClaimerOnly, stale, 3, 0.0, true});
  cases.push_back({"full-bucket-masked", Defect::kFullBucketMasked, buckets, 1, 0.0, true});
  cases.push_back({"weak-cas-old-value", Defect::kWeakCasOldValue, buckets, 1, 0.25, true});
  // Full keys: 64-bit identities and tags in the capture (flag bit 2), clean and matched by their low word.
  FilterConfig full = evicting;
  full.fingerprint_bits = 32;
  full.key_identity = KeyIdentity::kFull;
  cases.push_back({"clean crowded full keys stale:1 ema, 3 frames", Defect::kNone, full, 3});
  FilterConfig full_one_frame = Crowded();
  full_one_frame.fingerprint_bits = 32;
  full_one_frame.key_identity = KeyIdentity::kFull;
  cases.push_back({"full-key-low-word", Defect::kFullKeyLowWord, full_one_frame, 1, 0.0, true});
  // packed-decimal sums: 32-bit sums and count words in the capture (flag bit 3), clean and with D9's lost adds.
  FilterConfig packed = Crowded();
  packed.accumulation = Accumulation::kPackedDecimal;
  packed.eviction = ParseEviction("stale:1");
  packed.compaction = Compaction::kOccupiedList;
  cases.push_back({"clean crowded packed-decimal stale:1, occupied list, 3 frames", Defect::kNone, packed, 3});
  FilterConfig packed_roomy = Roomy();
  packed_roomy.accumulation = Accumulation::kPackedDecimal;
  cases.push_back({"D9 packed-decimal", Defect::kD9NonAtomicAdd, packed_roomy, 1, 0.0, true});
  return cases;
}

// The host's verdict on the frames, and the judge's on each frame captured from that very run.
void ExpectTheJudgeGivesTheHostsVerdict(Crosschecker& checker, const HostCase& c, const EmulatorOptions& emulator,
                                        const std::string& backend) {
  const std::string dir = CaptureDir(backend + "-" + std::to_string(std::hash<std::string>()(c.name)));
  FilterConfig config = c.config;
  config.frames = c.frames;
  checker.ObserveFrames([&](const std::string& name, const RecordBatch& batch, std::uint32_t frame,
                            const HashedRun& run, const HashTableDump* before) {
    WriteRunCapture(dir + "/" + name + "-frame-" + std::to_string(frame) + ".hpsfc", TableDeclarationText(config),
                    batch, frame, run, before);
  });
  const std::vector<RecordBatch> frames = TracedFrames(LoadScene("cornell"), 32, 2, c.frames);
  const CrosscheckReport host = checker.CheckFrames(frames, config, emulator);
  checker.ObserveFrames({});
  std::set<int> judged_failed;
  for (std::uint32_t frame = 0; frame < c.frames; ++frame) {
    const std::string path = dir + "/" + backend + "-frame-" + std::to_string(frame) + ".hpsfc";
    ASSERT_TRUE(std::filesystem::exists(path)) << c.name << ": " << path;
    const CrosscheckReport judged = Judged(path);
    for (int level : FailedLevels(judged)) judged_failed.insert(level);
    EXPECT_FALSE(judged.levels[3].applicable) << c.name;
  }
  std::set<int> host_failed = FailedLevels(host);
  EXPECT_EQ(host_failed, judged_failed) << c.name << ": host " << host.FirstFailure();
  EXPECT_EQ(!host.Passed(), c.host_fails) << c.name << ": " << host.FirstFailure();
}

TEST(CaptureJudgement, TheJudgeGivesTheEmulatorsVerdictForEveryKernel) {
  EmulatorOptions faithful;
  faithful.mode = simt::Mode::kFaithful;
  faithful.warp_size = 8;
  faithful.schedule = "random:1";
  for (const HostCase& c : EmulatorCases()) {
    EmulatorOptions emulator = faithful;
    emulator.spurious_cas = c.spurious_cas;
    Crosschecker checker({"reference", "emulated"}, c.defect);
    ExpectTheJudgeGivesTheHostsVerdict(checker, c, emulator, "emulated");
  }
}

TEST(CaptureJudgement, TheJudgeGivesTheVulkanHostsVerdictForEveryShader) {
  // The shader variants whose failure is the same on every run (a race may show on a run and not on its rerun, which
  // no capture holds).
  const std::vector<std::pair<std::string, HostCase>> shaders = {
      {"", {"built-in shader, crowded", Defect::kNone, Crowded()}},
      {"",
       {"built-in shader, stale:1, 3 frames", Defect::kNone,
        [] {
          FilterConfig config = Crowded();
          config.eviction = ParseEviction("stale:1");
          return config;
        }(),
        3}},
      {"",
       {"built-in shader, packed-decimal, 3 frames", Defect::kNone,
        [] {
          FilterConfig config = Crowded();
          config.accumulation = Accumulation::kPackedDecimal;
          config.eviction = ParseEviction("stale:1");
          return config;
        }(),
        3}},
      {"D2", {"D2 shader", Defect::kNone, Crowded(), 1, 0.0, true}},
      {"D3", {"D3 shader", Defect::kNone, Crowded(), 1, 0.0, true}},
      {"D11",
       {"D11 shader", Defect::kNone,
        [] {
          FilterConfig config = Roomy();
          config.fixed_point_bits = 4;
          return config;
        }(),
        1, 0.0, true}},
  };
  for (const auto& [variant, c] : shaders) {
    VulkanBackendOptions vulkan;
    if (!variant.empty())
      vulkan.accumulate_spv = std::string(HPSF_SHADER_VARIANT_DIR) + "/accumulate_" + variant + ".spv";
    Crosschecker checker({"reference", "vulkan"}, Defect::kNone, vulkan);
    ExpectTheJudgeGivesTheHostsVerdict(checker, c, EmulatorOptions{}, "vulkan");
  }
}

// A team's own cache, written the way an engine would: keys of two words hashed by its own functions (not hpsf's),
// aligned buckets of 8 from the home slot, fixed-point sums at 2^20, a record inserted in order. Each Bug is one a
// production cache shipped (docs/design/defects.md, "Shipped bugs") or the classic races.
enum class Bug {
  kNone,
  kZeroIdentity,         // Bevy #21953: a checksum that may be 0, the empty marker
  kHomeOutsideTable,     // the home slot not masked to the table
  kFailureIntoSlotZero,  // a failed insert added to slot 0 (SHaRC's once)
  kMaskedIntoLastSlot,   // SHaRC #4: a full bucket's invalid index masked into the last slot, and added there
  kLostUpdate,           // one record's add lost (a non-atomic add)
  kSplitCell,            // a cell's later records claim a second slot (a claim race lost)
  kKeyNotAFunction,      // one record of a cell hashed with another seed
  kClusteredHomes,       // a home hash that reaches an eighth of the table: correct, but buckets overflow
};

constexpr std::uint32_t kBucket = 8;
constexpr int kFractionBits = 20;

struct TeamCapture {
  std::uint32_t capacity;
  std::uint32_t identity_bits;
  std::vector<float> contributions;
  std::vector<std::uint32_t> keys, home, identities, statuses, placements, tags;
  std::vector<std::uint64_t> sums, counts;
};

std::uint32_t TeamHash(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
  std::uint32_t h = seed ^ (x * 0x9E3779B1u);
  h = (h ^ (h >> 15)) * 0x85EBCA77u;
  h ^= y * 0xC2B2AE3Du;
  h = (h ^ (h >> 13)) * 0x27D4EB2Fu;
  return h ^ (h >> 16);
}

TeamCapture TeamFrame(std::uint32_t capacity, std::uint32_t identity_bits, Bug bug) {
  TeamCapture t{capacity,
                identity_bits,
                {},
                {},
                {},
                {},
                {},
                {},
                std::vector<std::uint32_t>(capacity, 0u),
                std::vector<std::uint64_t>(3 * std::size_t(capacity), 0u),
                std::vector<std::uint64_t>(capacity, 0u)};
  constexpr std::uint32_t kRecords = 600, kCells = 150;
  const std::uint32_t bug_cell = shared::Pcg(101) % kCells;  // record 101's cell, which has several records
  std::uint32_t bug_cell_records = 0;
  for (std::uint32_t i = 0; i < kRecords; ++i) {
    const std::uint32_t cell = shared::Pcg(i) % kCells;
    const std::uint32_t x = cell % 10, y = cell / 10;
    const bool sky = i % 17 == 0;
    const bool bug_record = cell == bug_cell && !sky;
    bug_cell_records += bug_record;
    std::uint32_t home = TeamHash(x, y, 1u) & (capacity - 1u);
    std::uint32_t identity = TeamHash(x, y, 2u) >> (32u - identity_bits);
    identity = std::max(identity, 1u);
    if (bug == Bug::kZeroIdentity && bug_record) identity = 0;
    if (bug == Bug::kHomeOutsideTable && bug_record) home += capacity;
    if (bug == Bug::kClusteredHomes) home &= capacity / 8 - 1;
    if (bug == Bug::kKeyNotAFunction && bug_record && bug_cell_records % 2 == 0) {
      identity = std::max(TeamHash(x, y, 3u) >> (32u - identity_bits), 1u);
    }
    const float c[3] = {float(i % 5) * 0.25f, float(cell) / 16.0f, 1.0f / float(1 + i % 3)};
    t.contributions.insert(t.contributions.end(), c, c + 3);
    t.keys.push_back(x);
    t.keys.push_back(y);
    t.home.push_back(home);
    t.identities.push_back(identity);
    t.statuses.push_back(sky ? capture::kNoVertex : capture::kKeyed);
    if (sky) {
      t.placements.push_back(capture::kNotPlaced);
      continue;
    }
    std::uint32_t placed = capture::kProbeFailure;
    const std::uint32_t first = (home & ~(kBucket - 1u)) % capacity;
    bool split = bug == Bug::kSplitCell && bug_record && bug_cell_records > 2;
    for (std::uint32_t probe = 0; probe < kBucket; ++probe) {
      const std::uint32_t s = first + probe;
      if (t.tags[s] == identity && !split) {
        placed = s;
        break;
      }
      if (t.tags[s] == 0) {
        t.tags[s] = identity;
        placed = s;
        break;
      }
      if (t.tags[s] == identity) split = false;  // passes its own slot once, then claims the next empty one
    }
    if (placed == capture::kProbeFailure && bug == Bug::kFailureIntoSlotZero) placed = 0;
    if (placed == capture::kProbeFailure && bug == Bug::kMaskedIntoLastSlot) placed = 0xFFFFFFFFu & (capacity - 1u);
    t.placements.push_back(placed);
    if (placed == capture::kProbeFailure) continue;
    if (bug == Bug::kLostUpdate && i == 401) continue;
    for (int ch = 0; ch < 3; ++ch) {
      t.sums[3 * placed + std::size_t(ch)] += shared::ToFixedPoint(c[ch], shared::PowerOfTwo(kFractionBits));
    }
    ++t.counts[placed];
  }
  return t;
}

// The team's frame as the writer takes it (spans over `t`, which must outlive it), its declaration left to the caller.
capture::FrameCapture FrameOf(const TeamCapture& t) {
  capture::FrameCapture c;
  c.capacity = t.capacity;
  c.fixed_point_bits = kFractionBits;
  c.key_words = 2;
  c.contributions = t.contributions;
  c.keys = t.keys;
  c.home_slots = t.home;
  c.identities = t.identities;
  c.statuses = t.statuses;
  c.placements = t.placements;
  c.after = {t.tags, t.sums, {}, t.counts, {}, {}, {}, {}};
  return c;
}

std::string TeamCaptureFile(std::uint32_t capacity, std::uint32_t identity_bits, Bug bug) {
  const TeamCapture t = TeamFrame(capacity, identity_bits, bug);
  const std::string declaration =
      R"({"hpsf_table": 1, "capacity": )" + std::to_string(capacity) +
      R"(, "probing": "bucket:8", "key": {"identity": "fingerprint", "fingerprint_bits": )" +
      std::to_string(identity_bits) + R"(}, "sums": {"encoding": "fixed64"}})";
  capture::FrameCapture c = FrameOf(t);
  c.declaration = declaration;
  // One file per test: ctest runs the tests of this binary side by side, each in a process of its own.
  const std::string path =
      ::testing::TempDir() + "/team-" + ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".hpsfc";
  EXPECT_EQ(capture::WriteCapture(path, c), "");
  return path;
}

CrosscheckReport JudgedTeamFrame(std::uint32_t capacity, std::uint32_t identity_bits, Bug bug) {
  return Judged(TeamCaptureFile(capacity, identity_bits, bug));
}

TableStatistics TeamKeyStatistics(std::uint32_t capacity, Bug bug) {
  const Capture capture = ReadCapture(TeamCaptureFile(capacity, 32, bug));
  FilterConfig config;
  ApplyTableDeclarationText(capture.declaration, capture.path, config);
  return MeasureGivenKeyStatistics(capture.record_count(), CapturedKeys(capture), config);
}

std::string AllFailures(const CrosscheckReport& report) {
  std::string all;
  for (const LevelVerdict& v : report.levels) {
    for (const std::string& f : v.failures) all += "level " + std::to_string(v.level) + ": " + f + "\n";
  }
  return all;
}

TEST(CaptureJudgement, ATeamsOwnKeysPassRoomyAndCrowded) {
  const CrosscheckReport roomy = JudgedTeamFrame(1024, 32, Bug::kNone);
  EXPECT_TRUE(roomy.Passed()) << AllFailures(roomy);
  EXPECT_EQ(roomy.quality[0].probe_failures, 0u);
  EXPECT_EQ(roomy.quality[0].aliased_slots, 0u);
  // 150 cells in 64 slots with 8-bit identities: buckets overflow and identities alias, and both are classified.
  const CrosscheckReport crowded = JudgedTeamFrame(64, 8, Bug::kNone);
  EXPECT_TRUE(crowded.Passed()) << AllFailures(crowded);
  EXPECT_GT(crowded.quality[0].probe_failures, 0u);
  EXPECT_GT(crowded.quality[0].aliased_slots, 0u);
}

TEST(CaptureJudgement, EachBugOfATeamsCacheIsNamedAtItsLevel) {
  struct Expected {
    Bug bug;
    std::uint32_t capacity;
    std::set<int> levels;
    std::string named;
  };
  const std::vector<Expected> bugs = {
      {Bug::kZeroIdentity, 256, {1, 2, 3}, "identity 0, the empty slot's marker"},
      {Bug::kHomeOutsideTable, 256, {1, 2}, "outside the table of 256 slots"},
      {Bug::kFailureIntoSlotZero, 64, {2}, "not among its bucket:8 candidates"},
      {Bug::kMaskedIntoLastSlot, 64, {2}, "slot0"},
      {Bug::kLostUpdate, 256, {2, 3}, "count"},
      {Bug::kSplitCell, 256, {2, 3}, "is split: its"},
      {Bug::kKeyNotAFunction, 256, {1, 3}, "share their key words but not their identity"},
  };
  for (const Expected& e : bugs) {
    const CrosscheckReport report = JudgedTeamFrame(e.capacity, 32, e.bug);
    EXPECT_EQ(FailedLevels(report), e.levels) << int(e.bug) << "\n" << AllFailures(report);
    EXPECT_NE(AllFailures(report).find(e.named), std::string::npos) << int(e.bug) << "\n" << AllFailures(report);
  }
}

// hpsf stats on a team's keys: its home slots against uniform hashing under its scheme. A home hash that reaches an
// eighth of the table is a correct table (the contract holds) whose buckets overflow far above the binomial theory;
// the alternative rejected is exactly such non-uniformity. The rates are held at a family level of 0.001 (Sidak over
// the probe limits and the one width), on this fixed input, so the uniform hash passing is deterministic.
TEST(CaptureJudgement, StatisticsOfATeamsKeysTellAClusteredHomeHash) {
  const TableStatistics uniform = TeamKeyStatistics(1024, Bug::kNone);
  EXPECT_FALSE(uniform.ExceedsTheory());
  EXPECT_TRUE(uniform.jitter.empty());
  ASSERT_EQ(uniform.fingerprints.size(), 1u);  // the declared width alone
  EXPECT_EQ(uniform.fingerprints[0].fingerprint_bits, 32u);
  EXPECT_TRUE(JudgedTeamFrame(1024, 32, Bug::kClusteredHomes).Passed());
  const TableStatistics clustered = TeamKeyStatistics(1024, Bug::kClusteredHomes);
  EXPECT_TRUE(clustered.ExceedsTheory());
  bool failures_exceed = false;
  for (const ProbeLimitFigure& f : clustered.probe_limits) failures_exceed |= f.failures.ExceedsTheory();
  EXPECT_TRUE(failures_exceed);
}

TEST(CaptureJudgement, ACaptureThatContradictsItsDeclarationIsBadInput) {
  const TeamCapture t = TeamFrame(64, 32, Bug::kNone);
  capture::FrameCapture c = FrameOf(t);
  const std::vector<std::pair<std::string, std::string>> declarations = {
      {R"({"hpsf_table": 1, "capacity": 128})", "the table has 64 slots, its declaration 128"},
      {R"({"hpsf_table": 1, "capacity": 64, "sums": {"encoding": "float32"}})",
       "the sums are fixed64, its declaration's float32"},
      {R"({"hpsf_table": 1, "capacity": 64, "passes": {"eviction": "strict"}})",
       "its declaration evicts, but the tables carry no last-seen frames"},
      {R"({"hpsf_table": 1, "capacity": 64, "passes": {"level_change": "seed"}})", "level seeding"},
      {R"({"hpsf_table": 1, "capacity": 64, "key": {"identity": "full"}})",
       "its declaration stores full keys (key.identity full), but the identities and tags are 32-bit"},
      {R"({"hpsf_table": 1, "capacity": 64, "passes": {"compaction": "occupied-list"}})",
       "its declaration compacts (passes.compaction occupied-list), but the capture holds no OCCL list"},
      // F 100 with contributions near 1: c x 2^100 is past fixed64, where the conversion is undefined.
      {R"({"hpsf_table": 1, "capacity": 64})", "--fixed-point-bits: F 100 is too large for a contribution"},
  };
  for (const auto& [declaration, named] : declarations) {
    c.declaration = declaration;
    c.fixed_point_bits = named.rfind("--fixed", 0) == 0 ? 100 : kFractionBits;
    const std::string path = ::testing::TempDir() + "/contradicting.hpsfc";
    ASSERT_EQ(capture::WriteCapture(path, c), "");
    try {
      Judged(path);
      ADD_FAILURE() << declaration;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ": " + named), std::string::npos) << e.what();
    }
  }
}

// A team's list of occupied slots, captured beside its table: the judge holds it to the table (kOccupiedList), and a
// list the declaration does not call for is bad input.
TEST(CaptureJudgement, ATeamsOccupiedListIsHeldToItsTable) {
  const TeamCapture t = TeamFrame(64, 32, Bug::kNone);
  capture::FrameCapture c = FrameOf(t);
  c.declaration =
      R"({"hpsf_table": 1, "capacity": 64, "probing": "bucket:8", "passes": {"compaction": "occupied-list"}})";
  std::vector<std::uint32_t> occupied;
  for (std::uint32_t s = 0; s < 64; ++s) {
    if (c.after.tags[s] != 0) occupied.push_back(s);
  }
  std::reverse(occupied.begin(), occupied.end());  // in some order of the engine's: any is right
  ASSERT_GT(occupied.size(), 4u);
  const auto judge = [&](const std::vector<std::uint32_t>& list) {
    const std::span<const std::uint32_t> view = list;
    c.occupied = &view;
    const std::string path = ::testing::TempDir() + "/listed.hpsfc";
    EXPECT_EQ(capture::WriteCapture(path, c), "");
    return Judged(path);
  };
  const CrosscheckReport right = judge(occupied);
  EXPECT_TRUE(right.Passed()) << right.FirstFailure();
  std::vector<std::uint32_t> repeated = occupied;
  repeated.back() = occupied[2];  // one slot listed twice, another missed
  const CrosscheckReport twice = judge(repeated);
  EXPECT_EQ(FailedLevels(twice), std::set<int>{2});
  EXPECT_NE(
      twice.FirstFailure().find("occupied list differs from the occupied slots at slot " + std::to_string(occupied[2]) +
                                ": entry " + std::to_string(occupied.size() - 1) + " lists it again"),
      std::string::npos)
      << twice.FirstFailure();
  std::vector<std::uint32_t> short_list(occupied.begin() + 1, occupied.end());
  EXPECT_NE(judge(short_list).FirstFailure().find("but not in the list"), std::string::npos);
  c.declaration = R"({"hpsf_table": 1, "capacity": 64, "probing": "bucket:8"})";
  try {
    judge(occupied);
    ADD_FAILURE() << "a list beside a table that does not compact was judged";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the capture holds an occupied list (OCCL), but its declaration does not "
                                         "compact"),
              std::string::npos)
        << e.what();
  }
}

// The list a compacted frame's passes started from (OCCB), captured beside the table before it: an emulator
// sequence's own passes the judge, and the same list with one slot listed twice fails level 2 alone, naming the list
// before the frame.
TEST(CaptureJudgement, TheListBeforeTheFrameIsHeldToTheTableBefore) {
  FilterConfig config = Crowded();
  config.eviction = ParseEviction("stale:1");
  config.compaction = Compaction::kOccupiedList;
  config.frames = 2;
  const std::string dir = CaptureDir("list-before");
  Crosschecker checker({"reference", "emulated"});
  checker.ObserveFrames([&](const std::string& name, const RecordBatch& batch, std::uint32_t frame,
                            const HashedRun& run, const HashTableDump* before) {
    WriteRunCapture(dir + "/" + name + "-frame-" + std::to_string(frame) + ".hpsfc", TableDeclarationText(config),
                    batch, frame, run, before);
  });
  ASSERT_TRUE(checker.CheckFrames(TracedFrames(LoadScene("cornell"), 32, 2, 2), config, EmulatorOptions{}).Passed());
  const std::string path = dir + "/emulated-frame-1.hpsfc";
  Capture capture = ReadCapture(path);
  ASSERT_TRUE(capture.occupied_before);
  ASSERT_GT(capture.occupied_before->size(), 2u);
  EXPECT_FALSE(ReadCapture(dir + "/emulated-frame-0.hpsfc").occupied_before) << "frame 0 started from no table";
  FilterConfig declared;
  ApplyTableDeclarationText(capture.declaration, path, declared);
  const CrosscheckReport right = JudgeCapture(capture, declared);
  EXPECT_TRUE(right.Passed()) << right.FirstFailure();
  EXPECT_NE(right.levels[1].note.find("its occupied list held to it"), std::string::npos) << right.levels[1].note;
  std::vector<std::uint32_t>& list = *capture.occupied_before;
  list.back() = list[1];
  const CrosscheckReport twice = JudgeCapture(capture, declared);
  EXPECT_EQ(FailedLevels(twice), std::set<int>{2});
  EXPECT_NE(
      twice.FirstFailure().find("capture, before the frame: occupied list differs from the occupied slots at slot " +
                                std::to_string(list[1])),
      std::string::npos)
      << twice.FirstFailure();
}

// Level 4 between two captures of one frame: a rerun that repeats each record's count and sums passes, one whose
// cell holds other sums fails naming the record, and a capture of other inputs is no rerun at all.
TEST(CaptureJudgement, ARerunIsHeldToWhatARerunMustRepeat) {
  const TeamCapture t = TeamFrame(1024, 32, Bug::kNone);  // roomy: nothing fails or aliases, so sums are promised
  const std::string declaration = R"({"hpsf_table": 1, "capacity": 1024, "probing": "bucket:8"})";
  const auto read = [&](const TeamCapture& frame, const std::string& name) {
    capture::FrameCapture c = FrameOf(frame);
    c.declaration = declaration;
    const std::string path = ::testing::TempDir() + "/" + name + ".hpsfc";
    EXPECT_EQ(capture::WriteCapture(path, c), "");
    return ReadCapture(path);
  };
  const Capture first = read(t, "first");
  FilterConfig config;
  ApplyTableDeclarationText(declaration, "declaration", config);
  EXPECT_FALSE(JudgeCapture(first, config).levels[3].applicable);
  const CrosscheckReport same = JudgeCapture(first, config, &first);
  ASSERT_TRUE(same.levels[3].applicable);
  EXPECT_TRUE(same.Passed()) << same.FirstFailure();
  TeamCapture other = t;  // the same inputs, one cell's sums otherwise in the rerun's table
  std::uint32_t placed = 0;
  while (placed < t.placements.size() && t.placements[placed] >= 1024u) ++placed;
  ASSERT_LT(placed, t.placements.size());
  other.sums[3 * t.placements[placed]] += 1;
  const Capture rerun = read(other, "rerun");
  const CrosscheckReport differs = JudgeCapture(first, config, &rerun);
  EXPECT_EQ(FailedLevels(differs), std::set<int>{});  // levels 1 to 3 judge the first capture, which is right
  EXPECT_FALSE(differs.levels[3].passed);
  EXPECT_NE(differs.FirstFailure().find("record " + std::to_string(placed)), std::string::npos)
      << differs.FirstFailure();
  TeamCapture moved = t;  // other inputs: a record's contribution
  moved.contributions[4] += 1.0f;
  const Capture not_a_rerun = read(moved, "moved");
  try {
    JudgeCapture(first, config, &not_a_rerun);
    ADD_FAILURE() << "a capture of other inputs was judged as a rerun";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("moved.hpsfc: not a rerun of " + first.path +
                                         ": record 1's contribution, key, home slot, identity or status differs"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hpsf::testing
