// Amortized several filtered bounces (Meijer §4.4, A-nHPSF; tracer/path_continuation.h): each camera sample extends
// the path it kept from the frame before by one filtered vertex, so paths grow across frames and every vertex is
// filtered. Held to Meijer's precedence rule vertex by vertex, to the scene change that must drop the kept paths
// (a broken state that survives it is caught), to the thread count, and to the traced furnace on every backend.
// Label `bounces`.

#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/eviction.h"
#include "core/shared/record_layout.h"
#include "core/temporal.h"
#include "emulated/emulated_backend.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_backend.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

TraceOptions ContinuedTrace(std::uint32_t size, std::uint32_t spp, std::uint32_t depth) {
  TraceOptions trace;
  trace.width = trace.height = size;
  trace.samples_per_pixel = spp;
  trace.scattered = true;
  trace.continuation_depth = depth;
  return trace;
}

bool SameRecords(const std::vector<Record>& a, const std::vector<Record>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Record)) == 0;
}

// Record i's continued record: the last of its deeper ones, and the vertex it scattered to.
const Record& ContinuedRecord(const RecordBatch& batch, std::size_t i, std::size_t per_sample) {
  return batch.deeper[i * per_sample + per_sample - 1];
}
const Record& ContinuedScattered(const RecordBatch& batch, std::size_t i, std::size_t per_sample) {
  return batch.scattered[batch.records.size() + i * per_sample + per_sample - 1];
}

// The furnace is closed and every vertex goes on: with one filtered vertex at the primary hit, a frame's own path
// reaches vertex 1, so the kept path is vertex 1 after frame 0, and each later frame extends it by one vertex until it
// would reach the depth, when the frame's own vertex 1 is kept again: the continued record of frame k (k >= 1) is at
// vertex 1 + (k - 1) mod (depth - 1), and the vertex it scattered to one further. Frame 0 continues nothing.
TEST(Continuation, ThePrecedenceRuleKeepsTheDeepestPathBelowTheDepth) {
  const Scene furnace = LoadScene(HPSF_SCENES_DIR "/furnace.json");
  constexpr std::uint32_t kDepth = 4;
  TraceOptions trace = ContinuedTrace(8, 2, kDepth);
  PathContinuation continuation;
  for (std::uint32_t k = 0; k < 8; ++k) {
    trace.frame = k;
    const TraceResult traced = TraceRecords(furnace, trace, {}, &continuation);
    const RecordBatch& batch = traced.batch;
    ASSERT_EQ(batch.deeper.size(), batch.records.size());  // one filtered vertex: the continued record alone
    EXPECT_EQ(traced.stats.continued, k == 0 ? 0u : batch.records.size()) << "frame " << k;
    for (std::size_t i = 0; i < batch.records.size(); ++i) {
      const Record& r = ContinuedRecord(batch, i, 1);
      const Record& s = ContinuedScattered(batch, i, 1);
      if (k == 0) {
        EXPECT_FALSE(shared::RecordHasVertex(r)) << "record " << i;
        continue;
      }
      ASSERT_TRUE(shared::RecordHasVertex(r)) << "frame " << k << ", record " << i;
      ASSERT_TRUE(shared::RecordHasVertex(s)) << "frame " << k << ", record " << i;
      EXPECT_EQ(shared::RecordBounce(r), 1u + (k - 1) % (kDepth - 1)) << "frame " << k << ", record " << i;
      EXPECT_EQ(shared::RecordBounce(s), shared::RecordBounce(r) + 1) << "frame " << k << ", record " << i;
      EXPECT_EQ(r.path.x, batch.records[i].path.x);
      EXPECT_EQ(r.path.y, batch.records[i].path.y);
    }
  }
}

// Whether frame `frame` of `scene`, traced after `before` (a state that frame - 1 of another scene left), gives the
// records of the same frame traced with no kept paths.
bool TracesAsIfNothingWasKept(const Scene& before, const Scene& scene, std::uint32_t frame, PathContinuation state) {
  TraceOptions trace = ContinuedTrace(8, 2, 6);
  trace.frame = frame - 1;
  TraceRecords(before, trace, {}, &state);
  trace.frame = frame;
  const RecordBatch kept = TraceRecords(scene, trace, {}, &state).batch;
  PathContinuation none;
  const RecordBatch fresh = TraceRecords(scene, trace, {}, &none).batch;
  return SameRecords(kept.deeper, fresh.deeper) && SameRecords(kept.scattered, fresh.scattered) &&
         SameRecords(kept.records, fresh.records);
}

// A kept path is valid only in the frame after the one that kept it, of the same scene: a camera cut, a moved box
// (cornell-animated's keyframes) or a skipped frame drops every sample's, so the frame traces as if nothing was kept.
// The broken state that survives a change of the scene continues paths the new scene does not hold and is caught;
// where nothing changed, the kept paths go on (the same frames differ from a fresh trace).
TEST(Continuation, AChangedSceneDropsTheKeptPaths) {
  const Scene cornell = LoadScene("cornell");
  Scene cut_scene = cornell;
  cut_scene.camera.position += glm::vec3(0.25f, 0.0f, 0.0f);
  const Scene& cut = cut_scene;
  const Scene animated = LoadScene(HPSF_SCENES_DIR "/cornell-animated.json");
  PathContinuation broken;
  broken.survives_scene_changes = true;
  for (const auto& [name, before, after] :
       {std::tuple{"a camera cut", &cornell, &cut}, std::tuple{"a moved box", &animated, &animated}}) {
    EXPECT_TRUE(TracesAsIfNothingWasKept(*before, *after, 3, PathContinuation{})) << name;
    EXPECT_FALSE(TracesAsIfNothingWasKept(*before, *after, 3, broken)) << name << ": the broken state is not caught";
  }
  EXPECT_FALSE(TracesAsIfNothingWasKept(cornell, cornell, 3, PathContinuation{})) << "a static scene's paths go on";
  // A skipped frame: frame 1 kept, frame 3 traced.
  TraceOptions trace = ContinuedTrace(8, 2, 6);
  PathContinuation state;
  trace.frame = 1;
  TraceRecords(cornell, trace, {}, &state);
  trace.frame = 3;
  EXPECT_EQ(TraceRecords(cornell, trace, {}, &state).stats.continued, 0u);
}

// The kept paths, like every record, do not depend on the thread count: three frames on one thread and on all.
TEST(Continuation, TheKeptPathsDoNotDependOnTheThreadCount) {
  const Scene cornell = LoadScene("cornell");
  TraceOptions one = ContinuedTrace(16, 2, 5), all = one;
  one.threads = 1;
  PathContinuation a, b;
  for (std::uint32_t k = 0; k < 3; ++k) {
    one.frame = all.frame = k;
    const RecordBatch x = TraceRecords(cornell, one, {}, &a).batch;
    const RecordBatch y = TraceRecords(cornell, all, {}, &b).batch;
    EXPECT_TRUE(SameRecords(x.records, y.records)) << "frame " << k;
    EXPECT_TRUE(SameRecords(x.deeper, y.deeper)) << "frame " << k;
    EXPECT_TRUE(SameRecords(x.scattered, y.scattered)) << "frame " << k;
  }
}

// A depth the frame's own path already reaches, or kept paths without the scattered vertices, are refused by name.
TEST(Continuation, ABadDepthIsNamed) {
  TraceOptions trace = ContinuedTrace(8, 1, 2);
  trace.filtered_vertices = 2;
  EXPECT_THROW(trace.Validate(), ConfigError);
  trace.continuation_depth = 3;
  EXPECT_NO_THROW(trace.Validate());
  trace.continuation_depth = 1025;
  EXPECT_THROW(trace.Validate(), ConfigError);
  trace.continuation_depth = 3;
  trace.filtered_vertices = 1;
  trace.scattered = false;
  try {
    trace.Validate();
    FAIL() << "kept paths without scattered vertices";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--continuation-depth"), std::string::npos) << e.what();
  }
}

// The traced furnace (radiance 2 everywhere) with one filtered vertex per frame and the transport, in a table that
// forgets its history: without kept paths most scattered vertices' cells are never filled (Transport.
// TheTracedFurnaceGainsOneBouncePerFrame: 78% of the lookups miss, the mean stays near 1.56); with kept paths of depth
// 8 every vertex they reach is filtered one frame later, the misses fall and the image mean approaches 2. Each frame on
// the reference, the emulator and Vulkan gives the same pixels (fixed64).
TEST(Continuation, KeptPathsFillTheCellsTheFurnacesLookupsMissed) {
  const Scene furnace = LoadScene(HPSF_SCENES_DIR "/furnace.json");
  constexpr std::uint32_t kFrames = 12;
  double means[2] = {0.0, 0.0}, misses[2] = {0.0, 0.0};
  for (const std::uint32_t depth : {0u, 8u}) {
    FilterConfig config;
    config.temporal = ParseTemporal("ema:0.000000000931322574615478515625");
    config.transport = true;
    config.frames = kFrames;
    config.capacity = 1u << 16;
    ReferenceBackend reference;
    EmulatedBackend emulated{EmulatorOptions{}};
    VulkanBackend vulkan{TestDevice(StagingPolicy::kNever)};
    TraceOptions trace = ContinuedTrace(32, 4, depth);
    PathContinuation continuation;
    for (std::uint32_t k = 0; k < kFrames; ++k) {
      trace.frame = config.frame = k;
      const RecordBatch batch = TraceRecords(furnace, trace, {}, &continuation).batch;
      const Image& image = reference.FilterFrame(batch, config);
      EXPECT_EQ(emulated.FilterFrame(batch, config).pixels, image.pixels) << "depth " << depth << ", frame " << k;
      EXPECT_EQ(vulkan.FilterFrame(batch, config).pixels, image.pixels) << "depth " << depth << ", frame " << k;
      double mean = 0.0;
      for (const glm::vec3& pixel : image.pixels) mean += double(pixel.x);
      mean /= double(image.pixels.size());
      const TransportStats& t = reference.LastExactResult()->stats.transport;
      std::printf("continuation depth %u, frame %2u: image mean %.5f; %llu scattered, %llu found, %llu missed\n", depth,
                  k, mean, (unsigned long long)t.scattered, (unsigned long long)t.found, (unsigned long long)t.missed);
      means[depth > 0] = mean;
      misses[depth > 0] = t.scattered > 0 ? double(t.missed) / double(t.scattered) : 0.0;
      EXPECT_LE(mean, 2.0 + 0.005) << "depth " << depth << ", frame " << k;
    }
  }
  EXPECT_GT(misses[0], 0.5);
  EXPECT_LT(misses[1], 0.5 * misses[0]);
  EXPECT_GT(means[1], means[0] + 0.1);
}

// Eviction under kept paths: cells are no longer added to every frame but still carry light (Meijer §4.4). In the
// furnace every sample's kept path is at the same vertex in a frame, so a deeper vertex's cell (coarser, under level
// of detail) is added to about once in a cycle of depth - 1 frames, and a lookup reads it in between. `stale:N` keeps
// a cell N frames after its last add: N >= depth - 1 keeps what a cycle revisits, `strict` (N = 1) forgets it before
// the next lookup. Measured over 12 frames at depth 8 (frames 4 to 11; docs/design/algorithm.md): none misses 1.3% of
// the lookups, stale:7 1.5%, stale:2 15%, strict 23%, and the image mean falls from 1.987 to 1.819 with them.
TEST(Continuation, EvictionMustOutlastAKeptPathsCycle) {
  const Scene furnace = LoadScene(HPSF_SCENES_DIR "/furnace.json");
  constexpr std::uint32_t kFrames = 12, kDepth = 8;
  std::map<std::string, double> missed, mean;
  for (const std::string policy : {"none", "stale:7", "stale:2", "strict"}) {
    FilterConfig config;
    config.temporal = ParseTemporal("ema:0.000000000931322574615478515625");
    config.transport = true;
    config.frames = kFrames;
    config.capacity = 1u << 16;
    config.eviction = ParseEviction(policy);
    ReferenceBackend reference;
    TraceOptions trace = ContinuedTrace(32, 4, kDepth);
    PathContinuation continuation;
    std::uint64_t scattered = 0, misses = 0;
    for (std::uint32_t k = 0; k < kFrames; ++k) {
      trace.frame = config.frame = k;
      const Image& image = reference.FilterFrame(TraceRecords(furnace, trace, {}, &continuation).batch, config);
      const TransportStats& t = reference.LastExactResult()->stats.transport;
      if (k >= 4) scattered += t.scattered, misses += t.missed;
      mean[policy] = 0.0;
      for (const glm::vec3& pixel : image.pixels) mean[policy] += double(pixel.x) / double(image.pixels.size());
    }
    missed[policy] = double(misses) / double(scattered);
    std::printf("eviction %-8s: frames 4 to 11 missed %.4f of their lookups; image mean after frame 11 %.5f\n",
                policy.c_str(), missed[policy], mean[policy]);
  }
  EXPECT_LT(missed["stale:7"], missed["none"] + 0.005);
  EXPECT_GT(missed["stale:2"], 5.0 * missed["none"]);
  EXPECT_GT(missed["strict"], missed["stale:2"]);
  EXPECT_GT(mean["none"] - mean["strict"], 0.1);
}

}  // namespace
}  // namespace hpsf::testing
