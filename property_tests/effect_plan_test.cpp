// Effect planning (core/effect_plan.h): the plan skips a pass only where it changes no bit. On every
// backend, forcing each skipped effect (--force-effect) gives the same image and the same table, bit for bit, and
// the pass did run (its timer reads more than zero); the skipped pass's timer reads exactly zero. A static scene
// traced from one build gives the records of a build per frame.
//
// The cases where the plan skips: temporal and level-seed on a sequence's first frame (no history, an empty table
// to seed from); eviction before the frame it can first evict (strict and priority: frame 1; stale:N: frame N);
// level-seed where --level-min = --level-max (no cell has a parent or child). Each runs on a backend that filtered
// another sequence before (Reset between), so a forced pass that read a previous sequence's leftovers would show.

#include "core/effect_plan.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend_registry.h"
#include "core/error.h"
#include "emulated/emulated_backend.h"
#include "property_tests/hashed_backends.h"
#include "property_tests/traced_batch.h"
#include "reference/reference_backend.h"
#include "tracer/scene_file.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

TEST(EffectPlan, PlansEachPassByWhatTheFrameGivesIt) {
  FilterConfig config;
  config.temporal = ParseTemporal("ema:0.8");
  config.level_seed = ParseLevelSeed("seed");
  config.eviction = ParseEviction("stale:3");
  const FrameEffects first = PlanFrameEffects(config, 0), second = PlanFrameEffects(config, 1);
  EXPECT_FALSE(first.temporal);
  EXPECT_FALSE(first.level_seed);
  EXPECT_TRUE(second.temporal);
  EXPECT_TRUE(second.level_seed);
  for (std::uint32_t k = 0; k < 6; ++k) EXPECT_EQ(PlanFrameEffects(config, k).eviction, k >= 3) << k;
  EXPECT_TRUE(PlanFrameEffects(config, kLaterFrame).eviction);
  config.eviction = ParseEviction("priority");
  EXPECT_FALSE(PlanFrameEffects(config, 0).eviction);
  EXPECT_TRUE(PlanFrameEffects(config, 1).eviction);
  config.level_min = config.level_max = 3;
  EXPECT_FALSE(PlanFrameEffects(config, 5).level_seed);
  config.forced.Add(Effect::kLevelSeed);
  config.forced.Add(Effect::kTemporal);
  config.forced.Add(Effect::kEviction);
  EXPECT_TRUE(PlanFrameEffects(config, 0).level_seed);
  EXPECT_TRUE(PlanFrameEffects(config, 0).temporal);
  EXPECT_TRUE(PlanFrameEffects(config, 0).eviction);
  EXPECT_EQ(config.forced.ToString(), "temporal,level-seed,eviction");
  // The transport from the second frame on, or forced on the first, whose lookups all miss.
  config.transport = true;
  EXPECT_FALSE(PlanFrameEffects(config, 0).transport);
  EXPECT_TRUE(PlanFrameEffects(config, 1).transport);
  config.forced.Add(Effect::kTransport);
  EXPECT_TRUE(PlanFrameEffects(config, 0).transport);
  // Survival likewise: the tracer reads no table on the first frame unless forced, where every path survives.
  config.survival = ParseSurvival("linear:0.001:0.01");
  EXPECT_FALSE(PlanFrameEffects(config, 0).survival);
  EXPECT_TRUE(PlanFrameEffects(config, 1).survival);
  config.forced.Add(Effect::kSurvival);
  EXPECT_TRUE(PlanFrameEffects(config, 0).survival);

  // The sequence's decisions, with the frames each pass runs on and why.
  FilterConfig plain;
  plain.eviction = ParseEviction("stale:4");
  plain.temporal = ParseTemporal("adaptive");
  const std::vector<EffectDecision> static_plan = PlanSequenceEffects(plain, SceneFacts{true, false}, 4);
  ASSERT_EQ(static_plan.size(), kEffects.size());
  EXPECT_EQ(static_plan[0].frames_run, 0u);  // animation: one build
  EXPECT_NE(static_plan[0].reason.find("no keyframes"), std::string::npos) << static_plan[0].reason;
  EXPECT_EQ(static_plan[1].frames_run, 3u);  // temporal: frames 1 to 3, noted as not called for by a static scene
  EXPECT_NE(static_plan[1].reason.find("static"), std::string::npos) << static_plan[1].reason;
  EXPECT_FALSE(static_plan[2].asked);
  EXPECT_EQ(static_plan[3].frames_run, 0u);  // stale:4 over 4 frames evicts nothing
  EXPECT_NE(static_plan[3].reason.find("before frame 4"), std::string::npos) << static_plan[3].reason;
  const std::vector<EffectDecision> moving_plan = PlanSequenceEffects(plain, SceneFacts{true, true}, 6);
  EXPECT_EQ(moving_plan[0].frames_run, 6u);
  EXPECT_EQ(moving_plan[3].frames_run, 2u);  // frames 4 and 5
}

TEST(EffectPlan, ForcingNeedsAnEffectTheOptionsAskFor) {
  EXPECT_EQ(ParseEffect("level-seed"), Effect::kLevelSeed);
  EXPECT_THROW(ParseEffect("glossy"), ConfigError);
  for (Effect effect : {Effect::kTemporal, Effect::kLevelSeed, Effect::kEviction, Effect::kNeighbourSearch,
                        Effect::kTransport, Effect::kSurvival}) {
    FilterConfig config;
    config.forced.Add(effect);
    try {
      config.Validate();
      ADD_FAILURE() << EffectName(effect) << " forced without its option";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--force-effect: " + EffectName(effect), 0), 0u) << e.what();
    }
  }
  FilterConfig animation;
  animation.forced.Add(Effect::kAnimation);
  EXPECT_NO_THROW(animation.Validate());
}

// One skipped effect: the options asking for it, and the frames over which the plan skips it.
struct SkipCase {
  std::string name;
  Effect effect;
  std::uint32_t frames;
  void (*configure)(FilterConfig&);
};

const std::vector<SkipCase>& SkipCases() {
  static const std::vector<SkipCase> cases = {
      {"temporal on a single frame", Effect::kTemporal, 1,
       [](FilterConfig& c) { c.temporal = ParseTemporal("ema:0.5"); }},
      {"adaptive on a single frame", Effect::kTemporal, 1,
       [](FilterConfig& c) { c.temporal = ParseTemporal("adaptive"); }},
      {"level-seed on a single frame", Effect::kLevelSeed, 1,
       [](FilterConfig& c) { c.level_seed = ParseLevelSeed("seed:2"); }},
      {"level-seed on one level", Effect::kLevelSeed, 3,
       [](FilterConfig& c) {
         c.level_seed = ParseLevelSeed("seed");
         c.level_min = c.level_max = 4;  // every cell clamped to level 4
       }},
      {"strict on a single frame", Effect::kEviction, 1, [](FilterConfig& c) { c.eviction = ParseEviction("strict"); }},
      {"priority on a single frame", Effect::kEviction, 1,
       [](FilterConfig& c) {
         c.eviction = ParseEviction("priority");
         c.fingerprint_bits = 24;
       }},
      {"stale:3 over 3 frames", Effect::kEviction, 3, [](FilterConfig& c) { c.eviction = ParseEviction("stale:3"); }},
  };
  return cases;
}

// The phase timer of `effect` in the backend's last frame, in seconds; the reference has none (-1).
double PhaseSeconds(const Backend& backend, Effect effect) {
  if (!backend.LastHashedRun()) return -1.0;
  const FrameTimings t = backend.LastFrameTimings();
  return 1e-3 * (effect == Effect::kTemporal    ? t.temporal_ms
                 : effect == Effect::kLevelSeed ? t.level_seed_ms
                                                : t.eviction_ms);
}

// Every bit of the backend's last image and table. Where the slots and the float adds' order depend on timing (the
// contract's classified nondeterminism: Vulkan on any device), the table is compared as the set of its slots, and
// float32 images and sums not at all.
struct FrameBits {
  std::vector<float> pixels;
  std::vector<SlotTag> tags;
  std::vector<std::uint64_t> counts;
  std::vector<std::uint64_t> sums;  // fixed64 sums, or float32 sums' bits
  std::vector<std::uint32_t> last_seen;
  std::vector<std::uint32_t> placements;
};

// The slots of a table in an order of their own contents, not of where they lie.
std::vector<std::vector<std::uint64_t>> SlotSet(const HashTableDump& t, bool with_sums) {
  std::vector<std::vector<std::uint64_t>> slots;
  for (std::size_t s = 0; s < t.capacity; ++s) {
    std::vector<std::uint64_t> slot = {t.tags[s], t.counts[s], t.last_seen.empty() ? 0u : t.last_seen[s]};
    if (with_sums) slot.insert(slot.end(), t.fixed_sums[s].begin(), t.fixed_sums[s].end());
    slots.push_back(slot);
  }
  std::sort(slots.begin(), slots.end());
  return slots;
}

FrameBits BitsOf(const Backend& backend, const Image& image) {
  FrameBits bits;
  const bool timed = FindBackend(backend.Name(), "backend").on_device;
  if (const HashedRun* run = timed ? backend.LastHashedRun() : nullptr) {
    const bool fixed = run->table.accumulation == Accumulation::kFixed64;
    if (fixed) {
      for (const glm::vec3& p : image.pixels) bits.pixels.insert(bits.pixels.end(), {p.x, p.y, p.z});
    }
    for (const std::vector<std::uint64_t>& slot : SlotSet(run->table, fixed)) {
      bits.sums.insert(bits.sums.end(), slot.begin(), slot.end());
    }
    return bits;
  }
  for (const glm::vec3& p : image.pixels) bits.pixels.insert(bits.pixels.end(), {p.x, p.y, p.z});
  if (const HashedRun* run = backend.LastHashedRun()) {
    const HashTableDump& t = run->table;
    bits.tags = t.tags;
    bits.counts = t.counts;
    for (const auto& s : t.fixed_sums) bits.sums.insert(bits.sums.end(), s.begin(), s.end());
    for (const auto& s : t.float_sums) {
      for (float f : s) {
        std::uint32_t word = 0;
        std::memcpy(&word, &f, sizeof word);
        bits.sums.push_back(word);
      }
    }
    bits.last_seen = t.last_seen;
    bits.placements = run->placements;
  } else {
    const FilterResult& exact = *backend.LastExactResult();
    for (const TableCell& cell : exact.cells) {
      bits.tags.insert(bits.tags.end(), cell.key.begin(), cell.key.end());
      bits.counts.push_back(cell.count);
      bits.sums.insert(bits.sums.end(), cell.fixed_sum.begin(), cell.fixed_sum.end());
      for (float f : cell.float_sum) {
        std::uint32_t word = 0;
        std::memcpy(&word, &f, sizeof word);
        bits.sums.push_back(word);
      }
      bits.last_seen.push_back(cell.last_seen);
    }
    bits.placements = exact.placement;
  }
  return bits;
}

bool operator==(const FrameBits& a, const FrameBits& b) {
  return std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * 4) == 0 &&
         a.pixels.size() == b.pixels.size() && a.tags == b.tags && a.counts == b.counts && a.sums == b.sums &&
         a.last_seen == b.last_seen && a.placements == b.placements;
}

struct NamedBackend {
  std::string name;
  std::unique_ptr<Backend> backend;
};

TEST(EffectPlan, ForcingASkippedEffectGivesTheSameBitsAndASkippedOneSpendsNoTime) {
  const std::vector<RecordBatch> frames = TracedFrames(LoadScene("cornell"), 24, 2, 3);
  const std::vector<RecordBatch> other = TracedFrames(LoadScene("furnace"), 24, 2, 2);
  std::vector<NamedBackend> backends;
  backends.push_back({"reference", std::make_unique<ReferenceBackend>()});
  // The fast emulator on one worker, so its slots and float adds do not depend on timing.
  EmulatorOptions one_worker;
  one_worker.threads = 1;
  backends.push_back({"emulated fast, 1 thread", std::make_unique<EmulatedBackend>(one_worker)});
  for (HashedBackend& hashed : HashedBackends()) {
    if (hashed.name != "emulated fast") backends.push_back({hashed.name, std::move(hashed.backend)});
  }
  int forced_runs = 0;
  for (const SkipCase& skip : SkipCases()) {
    for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
      FilterConfig config;
      config.capacity = 4096;
      config.accumulation = accumulation;
      config.frames = skip.frames;
      skip.configure(config);
      FilterConfig forced = config;
      forced.forced.Add(skip.effect);
      for (NamedBackend& b : backends) {
        const std::string what = skip.name + ", " + ToString(accumulation) + ", " + b.name;
        // Leftovers of another sequence in the backend's buffers (its table and its double buffer).
        FilterConfig before = config;
        before.temporal = ParseTemporal("ema:0.5");
        before.level_seed = ParseLevelSeed("seed");
        before.level_min = -126;
        before.level_max = 126;
        before.frames = 2;
        for (std::uint32_t k = 0; k < skip.frames; ++k) {
          const std::string frame = what + ", frame " + std::to_string(k);
          // The sequence up to this frame, planned and forced, each after the other sequence.
          std::vector<FrameBits> bits;
          std::vector<double> seconds;
          for (const FilterConfig* c : {&config, &forced}) {
            b.backend->Reset();
            for (std::uint32_t j = 0; j < 2; ++j) b.backend->FilterFrame(other[j], before);
            b.backend->Reset();
            const Image* image = nullptr;
            for (std::uint32_t j = 0; j <= k; ++j) {
              FilterConfig at = *c;
              at.frame = j;
              image = &b.backend->FilterFrame(frames[j], at);
            }
            bits.push_back(BitsOf(*b.backend, *image));
            seconds.push_back(PhaseSeconds(*b.backend, skip.effect));
          }
          const FrameEffects planned = PlanFrameEffects(config, k);
          ASSERT_FALSE(skip.effect == Effect::kTemporal    ? planned.temporal
                       : skip.effect == Effect::kLevelSeed ? planned.level_seed
                                                           : planned.eviction)
              << frame << ": the case's effect is not skipped";
          EXPECT_TRUE(bits[0] == bits[1]) << frame << ": forcing the skipped effect changed the output";
          if (seconds[0] >= 0.0) {
            EXPECT_EQ(seconds[0], 0.0) << frame << ": the skipped pass's timer";
            EXPECT_GT(seconds[1], 0.0) << frame << ": the forced pass did not run";
            ++forced_runs;
          }
        }
      }
    }
  }
  EXPECT_GT(forced_runs, 0);
}

TEST(EffectPlan, AStaticSceneTracedFromOneBuildGivesTheRecordsOfABuildPerFrame) {
  const Scene scene = LoadScene("cornell");
  const PreparedScene prepared(scene, 0);
  for (std::uint32_t frame = 0; frame < 3; ++frame) {
    TraceOptions trace;
    trace.width = trace.height = 16;
    trace.samples_per_pixel = 2;
    trace.frame = frame;
    const RecordBatch once = TraceRecords(prepared, trace).batch, rebuilt = TraceRecords(scene, trace).batch;
    ASSERT_EQ(once.records.size(), rebuilt.records.size());
    EXPECT_EQ(std::memcmp(once.records.data(), rebuilt.records.data(), once.records.size() * sizeof(Record)), 0)
        << "frame " << frame;
  }
  // An animated scene's build is its frame's alone.
  const Scene animated = LoadScene(HPSF_SCENES_DIR "/cornell-animated.json");
  const PreparedScene frame0(animated, 0);
  TraceOptions trace;
  trace.width = trace.height = 8;
  trace.frame = 1;
  EXPECT_THROW(TraceRecords(frame0, trace), std::logic_error);
}

}  // namespace
}  // namespace hpsf::testing
