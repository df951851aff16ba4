// The HashCache's data and its sort-and-reduce update (core/hashcache_update.h): the front/back decision exact against
// real dot products; the reference's sums equal the samples' exact sums level by level; the emulator's update, in
// fast mode and under faithful schedules, in fixed64 and float32, is the reference's given its claims, bit for bit;
// the front claimed with a plain store and a reduce whose segment runs one element long are caught.
#include "core/hashcache_update.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/fixed_point_scale.h"
#include "core/hashcache_check.h"
#include "core/octahedral.h"
#include "core/shared/hashcache_cell.h"
#include "core/shared/rng.h"
#include "emulated/hashcache_update_kernels.h"
#include "property_tests/racing_schedules.h"
#include "property_tests/vulkan_test_devices.h"
#include "tracer/scene_file.h"
#include "vulkan/hashcache_update_pass.h"

namespace hpsf::testing {
namespace {

float Uniform(std::uint32_t seed, std::uint32_t i, std::uint32_t dimension) {
  return shared::RandomFloat(shared::RngCounter{seed, 0u, i, 0u, 0u}, dimension);
}

glm::vec3 RandomUnit(std::uint32_t seed, std::uint32_t i) {
  const float z = 2.0f * Uniform(seed, i, 0) - 1.0f;
  const float phi = 6.2831853f * Uniform(seed, i, 1);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

std::vector<OccupancyTriangle> CornellTriangles() {
  std::vector<OccupancyTriangle> triangles;
  for (const Triangle& t : LoadScene("cornell").triangles) triangles.push_back({t.p0, t.p1, t.p2});
  return triangles;
}

// `count` samples on the triangles, seen from either side (thin geometry: both sides lit), each normal tilted a
// little so that the side test has work to do, lights in [0, 2]; and two off the grid (far away, not a number).
std::vector<HashCacheSample> RandomSamples(const std::vector<OccupancyTriangle>& triangles, std::uint32_t count,
                                           std::uint32_t seed) {
  std::vector<HashCacheSample> samples;
  for (std::uint32_t i = 0; i < count; ++i) {
    const OccupancyTriangle& t =
        triangles[shared::RandomBits(shared::RngCounter{seed, 1u, i, 0u, 0u}, 0) % triangles.size()];
    float a = Uniform(seed, i, 2), b = Uniform(seed, i, 3);
    if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
    HashCacheSample s;
    s.position = t[0] + a * (t[1] - t[0]) + b * (t[2] - t[0]);
    glm::vec3 normal = glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
    if (Uniform(seed, i, 4) < 0.5f) normal = -normal;
    normal = glm::normalize(normal + 0.3f * RandomUnit(seed + 1000, i));
    s.normal = PackOctahedral16(normal);
    s.light = {2.0f * Uniform(seed, i, 5), 2.0f * Uniform(seed, i, 6), 2.0f * Uniform(seed, i, 7)};
    samples.push_back(s);
  }
  samples[count / 3].position = glm::vec3(1e30f);
  samples[count / 2].position.y = std::nanf("");
  return samples;
}

// An empty cache over the triangles at 2^resolution_log2 finest cells per axis, its maps the reference's.
HashCache EmptyCache(const std::vector<OccupancyTriangle>& triangles, int resolution_log2, Accumulation accumulation,
                     int fixed_point_bits) {
  const shared::OccupancyGrid grid = GridOver(triangles, resolution_log2, "test");
  std::vector<CuckooMap> maps;
  for (const OccupancyLevel& level : OccupancyPyramid(grid, triangles)) {
    const CuckooBuild build = BuildCuckooMap(OccupiedKeys(level), {.level = std::uint32_t(level.level())});
    EXPECT_TRUE(build.built);
    maps.push_back(build.map);
  }
  return EmptyHashCache(grid, std::move(maps), accumulation, fixed_point_bits);
}

int FixedPointBitsFor(const std::vector<HashCacheSample>& samples, std::uint32_t frames) {
  std::vector<glm::vec3> lights;
  for (const HashCacheSample& s : samples) lights.push_back(s.light);
  return ChooseFixedPointBitsOf(lights, {}, frames);
}

std::string First(const std::vector<std::string>& problems) { return problems.empty() ? "none" : problems[0]; }

// The side test on the fronts of real normals agrees with the sign of their exact dot product wherever it is
// clearly away from zero (the fronts quantize each normal by less than 2^-13); a front negated twice is itself and
// decodes to its vector negated, on the lattice's corners and on random words.
TEST(HashCacheCell, TheSideTestAgreesWithTheNormalsDotProducts) {
  int decided = 0;
  for (std::uint32_t i = 0; i < 20000; ++i) {
    const glm::vec3 a = RandomUnit(7, i), b = RandomUnit(8, i);
    const double dot = double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
    if (std::abs(dot) < 1e-3) continue;
    ++decided;
    ASSERT_EQ(shared::FacesFront(shared::FrontWord(PackOctahedral16(a)), shared::FrontWord(PackOctahedral16(b))),
              dot > 0)
        << i;
  }
  EXPECT_GT(decided, 19000);
  std::vector<std::uint32_t> fronts = {shared::kFrontClaimed, shared::kFrontClaimed | 0x7FFFu,
                                       shared::kFrontClaimed | (0x7FFFu << 15), 0xBFFFFFFFu,
                                       shared::FrontWord(PackOctahedral16({0.0f, 0.0f, -1.0f}))};
  for (std::uint32_t i = 0; i < 20000; ++i) {
    fronts.push_back(shared::kFrontClaimed | (shared::RandomBits(shared::RngCounter{9u, 0u, i, 0u, 0u}, 0) >> 2));
  }
  for (const std::uint32_t f : fronts) {
    const glm::ivec3 v = shared::FrontVector(f);
    ASSERT_EQ(std::abs(v.x) + std::abs(v.y) + std::abs(v.z), shared::kFrontScale) << f;
    ASSERT_EQ(shared::FrontVector(shared::NegatedFront(f)), -v) << f;
    ASSERT_EQ(shared::NegatedFront(shared::NegatedFront(f)), f) << f;
    ASSERT_FALSE(shared::FacesFront(shared::NegatedFront(f), f)) << f;
  }
}

// The reference over three frames of 3,000 samples on the Cornell box at 2^5 cells per axis, fixed64: every level's
// sums and counts equal the samples' exact sums summed directly, and each frame passes the frame check (its claims
// are its own). A sum changed by one unit is named.
TEST(HashCacheUpdate, TheReferencesSumsAreTheSamplesExactSums) {
  const std::vector<OccupancyTriangle> triangles = CornellTriangles();
  std::vector<HashCacheSample> all;
  for (std::uint32_t frame = 0; frame < 3; ++frame) {
    const std::vector<HashCacheSample> samples = RandomSamples(triangles, 3000, 10 + frame);
    all.insert(all.end(), samples.begin(), samples.end());
  }
  HashCache cache = EmptyCache(triangles, 5, Accumulation::kFixed64, FixedPointBitsFor(all, 1));
  std::uint64_t missed = 0;
  for (std::uint32_t frame = 0; frame < 3; ++frame) {
    const std::span<const HashCacheSample> samples(all.data() + 3000 * frame, 3000);
    const HashCache before = cache;
    const HashCacheUpdateReport report = UpdateHashCache(cache, samples);
    missed += report.missed;
    EXPECT_EQ(report.problems, std::vector<std::string>{});
    EXPECT_EQ(CheckHashCacheFrame(before, cache, samples), std::vector<std::string>{}) << "frame " << frame;
    if (frame == 0) {
      std::printf("frame 0: %zu segments per level, finest first:", report.segments.size());
      for (const std::uint64_t s : report.segments) std::printf(" %llu", (unsigned long long)s);
      std::printf("\n");
    }
  }
  EXPECT_EQ(CheckHashCacheSums(cache, all), std::vector<std::string>{});
  {
    // A front no sample of the frame claimed: a claim the checker must not take.
    HashCache empty = EmptyCache(triangles, 5, Accumulation::kFixed64, cache.fixed_point_bits);
    HashCache claimed = empty;
    const std::span<const HashCacheSample> first(all.data(), 3000);
    UpdateHashCache(claimed, first);
    std::size_t at = 0;
    while (claimed.levels[0].data.front[at] == shared::kFrontUnclaimed) ++at;
    claimed.levels[0].data.front[at] = shared::NegatedFront(claimed.levels[0].data.front[at]) ^ 1u;
    const std::vector<std::string> problems = CheckHashCacheFrame(empty, claimed, first);
    bool named = false;
    for (const std::string& p : problems) named |= p.find("is the side of no element") != std::string::npos;
    EXPECT_TRUE(named) << First(problems);
  }
  std::uint64_t two_sided = 0, cells = 0;
  const HashCacheData& finest = cache.levels[0].data;
  for (std::size_t slot = 0; slot < finest.front.size(); ++slot) {
    cells += finest.front[slot] != shared::kFrontUnclaimed;
    two_sided += finest.counts[2 * slot] != 0 && finest.counts[2 * slot + 1] != 0;
  }
  std::printf("9,000 samples: %llu missed (6 off the grid), %llu finest cells reached, %llu of them on both sides\n",
              (unsigned long long)missed, (unsigned long long)cells, (unsigned long long)two_sided);
  EXPECT_GE(missed, 6u);
  EXPECT_GT(two_sided, cells / 2);
  HashCache broken = cache;
  std::size_t at = 0;
  while (broken.levels[2].data.front[at] == shared::kFrontUnclaimed) ++at;
  broken.levels[2].data.fixed_sums[6 * at + 4] += 1;
  const std::vector<std::string> problems = CheckHashCacheSums(broken, all);
  ASSERT_EQ(problems.size(), 1u) << First(problems);
  std::printf("a sum of level 2 changed by one unit: %s\n", problems[0].c_str());
}

std::string Name(const EmulatorOptions& options) {
  return options.mode == simt::Mode::kFast ? "fast, " + std::to_string(options.threads) + " threads" : options.schedule;
}

// The emulator's update over two frames of 200 samples on the Cornell box at 2^3 cells per axis (so that many samples
// share a cell and race for its front), in fixed64 and float32, in fast mode on one and two workers and under the 40
// faithful schedules: every frame passes the frame check (the reference's update given the emulator's claims, bit for
// bit, float32's sums included), and fixed64's sums are the samples'. Which sample claims a front depends on the
// schedule: the claims differ from the reference's own under some schedules, so the check is fed claims other than
// the reference's.
TEST(HashCacheUpdate, TheEmulatorsUpdateIsTheReferencesGivenItsClaims) {
  const std::vector<OccupancyTriangle> triangles = CornellTriangles();
  std::vector<HashCacheSample> all = RandomSamples(triangles, 200, 20);
  const std::vector<HashCacheSample> second = RandomSamples(triangles, 200, 21);
  all.insert(all.end(), second.begin(), second.end());
  std::vector<EmulatorOptions> schedules = RacingSchedules();
  EmulatorOptions two;
  two.threads = 2;
  schedules.push_back(two);
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    const HashCache empty = EmptyCache(triangles, 3, accumulation, FixedPointBitsFor(all, 1));
    HashCache reference = empty;
    for (int frame = 0; frame < 2; ++frame) UpdateHashCache(reference, {all.data() + 200 * frame, 200});
    int other_claims = 0;
    for (const EmulatorOptions& options : schedules) {
      HashCache cache = empty;
      for (int frame = 0; frame < 2; ++frame) {
        const std::span<const HashCacheSample> samples(all.data() + 200 * frame, 200);
        const HashCache before = cache;
        const EmulatedHashCacheUpdate update = UpdateHashCacheEmulated(cache, samples, options);
        EXPECT_EQ(update.lost, 0u);
        const std::vector<std::string> problems = CheckHashCacheFrame(before, cache, samples);
        EXPECT_TRUE(problems.empty()) << Name(options) << ", frame " << frame << ": " << problems.size()
                                      << " problems, the first: " << First(problems);
      }
      if (accumulation == Accumulation::kFixed64) {
        EXPECT_EQ(CheckHashCacheSums(cache, all), std::vector<std::string>{}) << Name(options);
      }
      bool differs = false;
      for (std::size_t l = 0; l < cache.levels.size(); ++l) {
        differs |= cache.levels[l].data.front != reference.levels[l].data.front;
      }
      other_claims += differs;
    }
    std::printf("%s: the claims differ from the reference's own under %d of %zu schedules\n",
                ToString(accumulation).c_str(), other_claims, schedules.size());
    EXPECT_GT(other_claims, 0);
  }
}

// Broken updates, each caught by the frame check: the front claimed by a load and a store (under some of the 40
// faithful schedules: where two elements of a cell both read it unclaimed, each judges its side by its own normal
// while the cell keeps the last store's); and a reduce that adds the next segment's first element to its segment
// (in fast mode, every time).
TEST(HashCacheUpdate, BrokenUpdatesAreCaught) {
  const std::vector<OccupancyTriangle> triangles = CornellTriangles();
  const std::vector<HashCacheSample> samples = RandomSamples(triangles, 200, 30);
  const HashCache empty = EmptyCache(triangles, 3, Accumulation::kFixed64, FixedPointBitsFor(samples, 1));
  int caught = 0, faithful = 0;
  for (const EmulatorOptions& options : RacingSchedules()) {
    if (options.mode == simt::Mode::kFast) continue;
    ++faithful;
    HashCache cache = empty;
    UpdateHashCacheEmulated(cache, samples, options, HashCacheUpdateDefect::kPlainStoreClaim);
    const std::vector<std::string> problems = CheckHashCacheFrame(empty, cache, samples);
    if (!problems.empty() && caught++ == 0) {
      std::printf("%s, the plain-store claim: %zu problems, the first: %s\n", Name(options).c_str(), problems.size(),
                  problems[0].c_str());
    }
  }
  std::printf("the plain-store claim caught under %d of %d faithful schedules\n", caught, faithful);
  EXPECT_GT(caught, faithful / 2);
  HashCache cache = empty;
  UpdateHashCacheEmulated(cache, samples, EmulatorOptions{}, HashCacheUpdateDefect::kReduceOffByOne);
  const std::vector<std::string> problems = CheckHashCacheFrame(empty, cache, samples);
  ASSERT_FALSE(problems.empty());
  std::printf("the reduce one element long: %zu problems, the first: %s\n", problems.size(), problems[0].c_str());
}

// Every order of the finest level's locate launch for two samples in one cell with opposite normals, judged at the
// finest level (the levels above run round-robin, where the plain store's two segments race again): the plain-store
// claim is caught in some orders (those where both load the front before either stores it), the
// compare-and-swap in none.
TEST(HashCacheUpdate, EveryOrderOfTwoClaimsIsExplored) {
  const std::vector<OccupancyTriangle> triangles = CornellTriangles();
  std::vector<HashCacheSample> samples = RandomSamples(triangles, 8, 40);
  samples.resize(2);
  samples[1] = samples[0];
  samples[0].normal = PackOctahedral16(glm::vec3(0.0f, 1.0f, 0.0f));
  samples[1].normal = PackOctahedral16(glm::vec3(0.0f, -1.0f, 0.0f));
  const HashCache empty = EmptyCache(triangles, 3, Accumulation::kFixed64, FixedPointBitsFor(samples, 1));
  for (const auto defect : {HashCacheUpdateDefect::kNone, HashCacheUpdateDefect::kPlainStoreClaim}) {
    const Exploration e = ExploreEveryOrder(EmulatorOptions{}, [&](const EmulatorOptions& options) {
      HashCache cache = empty;
      UpdateHashCacheEmulated(cache, samples, options, defect);
      for (const std::string& problem : CheckHashCacheFrame(empty, cache, samples)) {
        if (problem.starts_with("level 0,")) return true;
      }
      return false;
    });
    std::printf("%s: caught in %llu of %llu orders\n",
                defect == HashCacheUpdateDefect::kNone ? "compare-and-swap" : "plain store",
                (unsigned long long)e.caught, (unsigned long long)e.schedules);
    if (defect == HashCacheUpdateDefect::kNone) {
      EXPECT_EQ(e.caught, 0u);
    } else {
      EXPECT_GT(e.caught, 0u);
    }
  }
}

// On Vulkan (mapped and staged): three frames of 3,000 samples on the Cornell box at 2^5 cells per axis, fixed64 and
// float32: every frame is the reference's given the device's claims, bit for bit (float32's sums included), and
// fixed64's sums are the samples'. The front claimed by a load and a store is caught.
TEST(HashCacheUpdate, TheDevicesUpdateIsTheReferencesGivenItsClaims) {
  const std::vector<OccupancyTriangle> triangles = CornellTriangles();
  std::vector<HashCacheSample> all;
  for (std::uint32_t frame = 0; frame < 3; ++frame) {
    const std::vector<HashCacheSample> samples = RandomSamples(triangles, 3000, 50 + frame);
    all.insert(all.end(), samples.begin(), samples.end());
  }
  for (const StagingPolicy staging : kStagingPolicies) {
    HashCacheUpdatePass pass(TestDevice(staging));
    const char* name = staging == StagingPolicy::kNever ? "mapped" : "staged";
    for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
      HashCache cache = EmptyCache(triangles, 5, accumulation, FixedPointBitsFor(all, 1));
      HashCache reference = cache;
      std::uint32_t missed = 0;
      for (std::uint32_t frame = 0; frame < 3; ++frame) {
        const std::span<const HashCacheSample> samples(all.data() + 3000 * frame, 3000);
        const HashCache before = cache;
        const DeviceHashCacheUpdate update = pass.Run(cache, samples);
        UpdateHashCache(reference, samples);
        missed += update.missed;
        EXPECT_EQ(update.lost, 0u);
        const std::vector<std::string> problems = CheckHashCacheFrame(before, cache, samples);
        EXPECT_TRUE(problems.empty()) << name << ", " << ToString(accumulation) << ", frame " << frame << ": "
                                      << problems.size() << " problems, the first: " << First(problems);
      }
      if (accumulation == Accumulation::kFixed64) {
        EXPECT_EQ(CheckHashCacheSums(cache, all), std::vector<std::string>{}) << name;
      }
      std::size_t other_fronts = 0;
      for (std::size_t l = 0; l < cache.levels.size(); ++l) {
        for (std::size_t slot = 0; slot < cache.levels[l].data.front.size(); ++slot) {
          other_fronts += cache.levels[l].data.front[slot] != reference.levels[l].data.front[slot];
        }
      }
      std::printf("%s, %s: 9,000 samples, %u missed; %zu fronts claimed other than the reference's own\n", name,
                  ToString(accumulation).c_str(), missed, other_fronts);
    }
    HashCache cache = EmptyCache(triangles, 5, Accumulation::kFixed64, FixedPointBitsFor(all, 1));
    const HashCache empty = cache;
    const std::span<const HashCacheSample> first(all.data(), 3000);
    pass.Run(cache, first, true);
    const std::vector<std::string> problems = CheckHashCacheFrame(empty, cache, first);
    EXPECT_FALSE(problems.empty()) << name;
    std::printf("%s, the plain-store claim: %zu problems, the first: %s\n", name, problems.size(),
                First(problems).c_str());
  }
}

// The atomics rule (every sample at every level, by atomic adds) on the reference, the emulator (fast mode on two
// workers and 10 faithful schedules) and Vulkan (mapped), two frames of 3,000 samples on the Cornell box at 2^5:
// every frame is the reference's given the backend's claims, and every level's fixed64 sums are its samples'. float32
// by atomics is refused.
TEST(HashCacheUpdate, TheAtomicsRuleOnEveryBackend) {
  const std::vector<OccupancyTriangle> triangles = CornellTriangles();
  std::vector<HashCacheSample> all = RandomSamples(triangles, 3000, 60);
  const std::vector<HashCacheSample> second = RandomSamples(triangles, 3000, 61);
  all.insert(all.end(), second.begin(), second.end());
  HashCache empty = EmptyCache(triangles, 5, Accumulation::kFixed64, FixedPointBitsFor(all, 1));
  empty.update = HashCacheUpdateRule::kAtomics;
  std::vector<EmulatorOptions> schedules = RacingSchedules();
  schedules.resize(10);
  EmulatorOptions two;
  two.threads = 2;
  schedules.push_back(two);
  HashCacheUpdatePass pass(TestDevice(StagingPolicy::kNever));
  // 0: the reference; 1 to 11: the emulator; 12: Vulkan.
  for (std::size_t run = 0; run < schedules.size() + 2; ++run) {
    const std::string name = run == 0 ? "reference" : run <= schedules.size() ? Name(schedules[run - 1]) : "vulkan";
    HashCache cache = empty;
    for (int frame = 0; frame < 2; ++frame) {
      const std::span<const HashCacheSample> samples(all.data() + 3000 * frame, 3000);
      const HashCache before = cache;
      if (run == 0) {
        UpdateHashCache(cache, samples);
      } else if (run <= schedules.size()) {
        UpdateHashCacheEmulated(cache, samples, schedules[run - 1]);
      } else {
        pass.Run(cache, samples);
      }
      const std::vector<std::string> problems = CheckHashCacheFrame(before, cache, samples);
      EXPECT_TRUE(problems.empty()) << name << ", frame " << frame << ": " << First(problems);
    }
    EXPECT_EQ(CheckHashCacheSums(cache, all), std::vector<std::string>{}) << name;
  }
  EXPECT_THROW(EmptyHashCache(empty.grid, {}, Accumulation::kFloat32, 0, 0, HashCacheUpdateRule::kAtomics),
               std::logic_error);
}

}  // namespace
}  // namespace hpsf::testing
