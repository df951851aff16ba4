// The HashCache as a renderer runs it (verifier/contract/hashcache_run.h): on every backend, constructions and updates
// that the family's checker passes frame after frame; construction only where the triangles changed (a static scene
// and a moving camera build once, a moving cube every frame); and the furnace's reconstructed image, whose every pixel
// has the exact expectation e + a e (1 - a^l_len) / (1 - a).
#include "verifier/contract/hashcache_run.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/footprint.h"
#include "property_tests/vulkan_test_devices.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf::testing {
namespace {

std::vector<OccupancyTriangle> TrianglesOf(const Scene& scene) {
  std::vector<OccupancyTriangle> triangles;
  for (const Triangle& t : scene.triangles) triangles.push_back({t.p0, t.p1, t.p2});
  return triangles;
}

TraceOptions Small(std::uint32_t frame) {
  TraceOptions trace;
  trace.width = trace.height = 24;
  trace.samples_per_pixel = 2;
  trace.frame = frame;
  return trace;
}

// Three frames of the Cornell box at 2^5 cells per axis, fixed64 and float32, on the reference, the emulator (fast
// mode, two workers) and Vulkan (mapped): the checker finds nothing in the construction or any update, and the cache
// is built once.
TEST(HashCacheRun, EveryBackendsFramesPassTheChecker) {
  const Scene scene = LoadScene("cornell");
  const PreparedScene prepared(scene, 0);
  EmulatorOptions two;
  two.threads = 2;
  for (const char* name : {"reference", "emulated", "vulkan"}) {
    for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
      const BackendInfo& info = FindBackend(name, "test");
      HashCacheRun run(info, {.resolution_log2 = 5, .accumulation = accumulation, .seed = 2, .frames = 3}, two,
                       info.kind == BackendKind::kVulkan ? &TestDevice(StagingPolicy::kNever) : nullptr);
      for (std::uint32_t frame = 0; frame < 3; ++frame) {
        run.Prepare(TrianglesOf(scene), "cornell");
        run.Update(TraceCacheSamples(prepared, Small(frame), {3, 3}).samples);
      }
      EXPECT_EQ(run.problems(), std::vector<std::string>{}) << name << ", " << ToString(accumulation);
      EXPECT_EQ(run.timings().builds, 1u) << name;
      std::printf(
          "%s, %s: 3 frames checked; construction %.1f ms (occupancy %.1f, maps %.1f, %u attempts over %zu "
          "levels), the last update %.1f ms\n",
          name, ToString(accumulation).c_str(), run.timings().occupancy_ms + run.timings().maps_ms,
          run.timings().occupancy_ms, run.timings().maps_ms, run.timings().attempts, run.cache().levels.size(),
          run.timings().update_ms);
    }
  }
}

// Effect planning: four frames of a camera dolly build once; four frames of cornell-animated (its cube and light move
// every frame) build four times.
TEST(HashCacheRun, ConstructionRunsWhereTheTrianglesChanged) {
  for (const auto& [name, builds] : {std::pair{"cornell-dolly", 1u}, std::pair{"cornell-animated", 4u}}) {
    const Scene scene = LoadScene(HPSF_SCENES_DIR "/" + std::string(name) + ".json");
    HashCacheRun run(FindBackend("reference", "test"), {.resolution_log2 = 6, .frames = 4});
    for (std::uint32_t frame = 0; frame < 4; ++frame) {
      const PreparedScene prepared(scene, frame);
      run.Prepare(TrianglesOf(prepared.scene()), name);
      run.Update(TraceCacheSamples(prepared, Small(frame), {2, 2}).samples);
    }
    EXPECT_EQ(run.timings().builds, builds) << name;
    EXPECT_EQ(run.problems(), std::vector<std::string>{}) << name;
    std::printf("%s: %u constructions in 4 frames; the last left %u of %zu levels' occupancy unchanged\n", name,
                run.timings().builds, run.timings().levels_unchanged, run.cache().levels.size());
  }
}

// The furnace (albedo a = 0.5, emission e = 1 everywhere) cached at l_len 3 over 4 frames and reconstructed at 32 x 32
// and 4 spp: a pixel sees e and its vertex's albedo times the cached light, whose expectation is e (1 - a^3) / (1 - a)
// = 1.75, so every pixel's expectation is 1.875. The image mean lies within 5 standard errors (pixel to pixel) of it;
// no lookup is left unfilled.
TEST(HashCacheRun, TheFurnacesReconstructionMeetsItsExactValue) {
  const Scene scene = LoadScene("furnace");
  const PreparedScene prepared(scene, 0);
  HashCacheRun run(FindBackend("reference", "test"), {.resolution_log2 = 5, .frames = 4});
  TraceOptions trace = Small(0);
  trace.width = trace.height = 32;
  trace.samples_per_pixel = 4;
  run.Prepare(TrianglesOf(scene), "furnace");
  for (std::uint32_t frame = 0; frame < 4; ++frame) {
    trace.frame = frame;
    run.Update(TraceCacheSamples(prepared, trace, {3, 3}).samples);
  }
  trace.max_depth = 1;
  const TraceResult primary = TraceRecords(prepared, trace);
  const HashCacheReconstruction image =
      run.Reconstruct(primary.batch, FootprintScale(4.0, primary.batch.fov_y_radians, trace.height), 1.0f, 4);
  double sum = 0.0, squares = 0.0;
  for (const glm::vec3& p : image.image.pixels) sum += p.x, squares += double(p.x) * p.x;
  const double n = double(image.image.pixels.size()), mean = sum / n;
  const double standard_error = std::sqrt((squares / n - mean * mean) / n);
  std::printf("the furnace reconstructed: mean %.5f +- %.5f (exact 1.875); %llu lookups, %.4f filled, %llu unfilled\n",
              mean, standard_error, (unsigned long long)image.lookups, image.FilledFraction(),
              (unsigned long long)image.unfilled);
  EXPECT_EQ(run.problems(), std::vector<std::string>{});
  EXPECT_LT(std::abs(mean - 1.875), 5.0 * standard_error);
  EXPECT_EQ(image.unfilled, 0u);
}

}  // namespace
}  // namespace hpsf::testing
