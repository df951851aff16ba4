// fuzz_hashcache: the HashCache's construction, update and checker over any scene and any samples the tracer could
// give. The input draws 1 to 12 triangles (coordinates of every kind: on cell lattices, huge, tiny, denormal, not
// finite, repeated), a resolution, an accumulation and update rule, and up to 256 samples per frame over one to three
// frames (on a triangle, off it, off the grid, not finite; any normal word; lights of every finite non-negative kind,
// as the tracer makes them). A scene no grid holds is refused (an InputError) and ends the input. A bug: a crash, a
// sanitizer report, a map that does not build at its default attempts, or a checker that finds a problem in the
// reference's own update or the emulator's (fast mode, or one faithful schedule drawn from the input): every frame
// is the reference's given the claims, and fixed64's sums are the samples' at every level.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "core/hashcache_check.h"
#include "core/hashcache_update.h"
#include "emulated/hashcache_update_kernels.h"

namespace hpsf {
namespace {

// wild: also huge, tiny, denormal and not finite values (a scene of them is mostly refused, so they are drawn rarely).
float Coordinate(FuzzedDataProvider& in, bool wild) {
  switch (in.ConsumeIntegralInRange(0, wild ? 5 : 2)) {
    case 0:
      return float(in.ConsumeIntegralInRange(-64, 64)) * 0.25f;  // on lattices of cells
    case 1:
      return in.ConsumeFloatingPointInRange(-1e3f, 1e3f);
    case 2:
      return float(in.ConsumeIntegralInRange(0, 8));
    case 3:
      return in.ConsumeFloatingPointInRange(-1e-30f, 1e-30f);
    case 4:
      return in.PickValueInArray({std::numeric_limits<float>::denorm_min(), -0.0f, 1e30f, -1e30f, 3e9f});
    default:
      return in.PickValueInArray({std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()});
  }
}

float Light(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 0:
      return 0.0f;
    case 1:
      return in.PickValueInArray({std::numeric_limits<float>::denorm_min(), 1e-38f, 1e30f, 65504.0f});
    default:
      return in.ConsumeFloatingPointInRange(0.0f, 4.0f);
  }
}

[[noreturn]] void Fail(const std::string& what, const std::vector<std::string>& problems) {
  std::fprintf(stderr, "fuzz_hashcache: %s: %zu problems, the first: %s\n", what.c_str(), problems.size(),
               problems.empty() ? "-" : problems[0].c_str());
  std::abort();
}

}  // namespace
}  // namespace hpsf

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hpsf;
  FuzzedDataProvider in(data, size);
  const bool wild_scene = in.ConsumeIntegralInRange(0, 15) == 0;
  std::vector<OccupancyTriangle> triangles(in.ConsumeIntegralInRange<std::size_t>(1, 12));
  for (OccupancyTriangle& t : triangles) {
    for (glm::vec3& v : t)
      v = glm::vec3(Coordinate(in, wild_scene), Coordinate(in, wild_scene), Coordinate(in, wild_scene));
    if (in.ConsumeBool()) t[2] = t[1];  // degenerate
  }
  const int resolution_log2 = in.ConsumeIntegralInRange(2, 8);
  shared::OccupancyGrid grid;
  try {
    grid = GridOver(triangles, resolution_log2, "fuzz");
  } catch (const InputError&) {
    return 0;
  }
  const Accumulation accumulation = in.ConsumeBool() ? Accumulation::kFixed64 : Accumulation::kFloat32;
  const HashCacheUpdateRule rule = accumulation == Accumulation::kFixed64 && in.ConsumeBool()
                                       ? HashCacheUpdateRule::kAtomics
                                       : HashCacheUpdateRule::kSortAndReduce;
  std::vector<CuckooMap> maps;
  for (const OccupancyLevel& level : OccupancyPyramid(grid, triangles)) {
    const CuckooBuild build = BuildCuckooMap(OccupiedKeys(level), {.level = std::uint32_t(level.level())});
    if (!build.built) Fail("level " + std::to_string(level.level()) + "'s map did not build", {});
    maps.push_back(build.map);
  }
  const std::uint32_t frames = in.ConsumeIntegralInRange(1, 3);
  std::vector<std::vector<HashCacheSample>> frame_samples(frames);
  std::vector<glm::vec3> lights;
  for (std::vector<HashCacheSample>& samples : frame_samples) {
    samples.resize(in.ConsumeIntegralInRange<std::size_t>(0, 256));
    for (HashCacheSample& s : samples) {
      const OccupancyTriangle& t = triangles[in.ConsumeIntegralInRange<std::size_t>(0, triangles.size() - 1)];
      const float a = in.ConsumeFloatingPointInRange(0.0f, 1.0f), b = in.ConsumeFloatingPointInRange(0.0f, 1.0f - a);
      s.position = in.ConsumeIntegralInRange(0, 7) == 0
                       ? glm::vec3(Coordinate(in, true), Coordinate(in, true), Coordinate(in, true))
                       : t[0] + a * (t[1] - t[0]) + b * (t[2] - t[0]);
      s.normal = in.ConsumeIntegral<std::uint32_t>();
      s.light = glm::vec3(Light(in), Light(in), Light(in));
      lights.push_back(s.light);
    }
  }
  const int bits = ChooseFixedPointBitsOf(lights);
  EmulatorOptions emulator;
  emulator.threads = 1;
  if (in.ConsumeBool()) {
    emulator.mode = simt::Mode::kFaithful;
    emulator.warp_size = in.PickValueInArray({1u, 4u, 8u});
    emulator.schedule = "random:" + std::to_string(in.ConsumeIntegral<std::uint16_t>());
  }
  const HashCache empty = EmptyHashCache(grid, maps, accumulation, bits, 0, rule);
  HashCache reference = empty, emulated = empty;
  std::vector<HashCacheSample> all;
  for (const std::vector<HashCacheSample>& samples : frame_samples) {
    const HashCache reference_before = reference, emulated_before = emulated;
    UpdateHashCache(reference, samples);
    UpdateHashCacheEmulated(emulated, samples, emulator);
    std::vector<std::string> problems = CheckHashCacheFrame(reference_before, reference, samples);
    if (!problems.empty()) Fail("the reference's own frame", problems);
    problems = CheckHashCacheFrame(emulated_before, emulated, samples);
    if (!problems.empty()) Fail("the emulator's frame", problems);
    all.insert(all.end(), samples.begin(), samples.end());
  }
  if (accumulation == Accumulation::kFixed64) {
    std::vector<std::string> problems = CheckHashCacheSums(reference, all);
    if (!problems.empty()) Fail("the reference's sums", problems);
    problems = CheckHashCacheSums(emulated, all);
    if (!problems.empty()) Fail("the emulator's sums", problems);
  }
  return 0;
}
