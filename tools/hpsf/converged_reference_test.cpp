// Converged references (tools/hpsf/converged_reference.h): the furnace, whose radiance is exactly 2 everywhere with
// unbounded depth, comes out at 2 within its own stated variance; the image is the same bits on one thread and on
// every core, and traced twice; a scene's digest follows its content, not its name.
#include "tools/hpsf/converged_reference.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include <gtest/gtest.h>

#include "tracer/scene_digest.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

ReferenceRequest FurnaceRequest() {
  ReferenceRequest request;
  request.trace.width = request.trace.height = 16;
  request.trace.max_depth = -1;
  request.samples_per_pixel = 64;
  request.pass_samples = 8;
  return request;
}

// The image mean per channel against 2, in units of its standard error from the pixels' variances (pixels are
// independent draws in plain path tracing). Rejects |z| > 4.5: a fixed seed, so the verdict never changes. Measured:
// mean 2.00769, standard error 0.00459 (0.23% of 2), z 1.68 in each channel; a bias of 2% would put |z| near 10.
TEST(ConvergedReference, TheFurnaceIsTwoWithinItsVariance) {
  const ReferenceRequest request = FurnaceRequest();
  const ConvergedImage image = RenderConverged(LoadScene("furnace"), request);
  for (int c = 0; c < 3; ++c) {
    double mean = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < image.mean.pixels.size(); ++i) {
      mean += image.mean.pixels[i][c];
      variance += image.variance.pixels[i][c];
    }
    const double n = double(image.mean.pixels.size());
    mean /= n;
    const double standard_error = std::sqrt(variance) / n;
    EXPECT_GT(standard_error, 0.0);
    EXPECT_LT(standard_error, 0.02 * 2.0 / 4.5) << "too noisy to see a 2% bias";
    EXPECT_LT(std::abs(mean - 2.0) / standard_error, 4.5) << "channel " << c << ": mean " << mean;
  }
}

TEST(ConvergedReference, TheSameBitsOnOneThreadOrEveryCoreAndTracedTwice) {
  ReferenceRequest request = FurnaceRequest();
  request.trace.max_depth = 8;
  const Scene scene = LoadScene("cornell");
  const ConvergedImage all = RenderConverged(scene, request);
  request.trace.threads = 1;
  const ConvergedImage one = RenderConverged(scene, request);
  EXPECT_TRUE(SameBits(all.mean, one.mean));
  EXPECT_TRUE(SameBits(all.variance, one.variance));
  EXPECT_TRUE(SameBits(RenderConverged(scene, request).mean, one.mean));
}

TEST(ConvergedReference, TheDigestFollowsTheContent) {
  const Scene cornell = LoadScene("cornell");
  Scene moved = cornell;
  moved.triangles[3].p1.x = std::nextafter(moved.triangles[3].p1.x, 1e9f);
  Scene renamed = cornell;
  renamed.name = "another name";
  EXPECT_EQ(SceneDigest(cornell, 0), SceneDigest(renamed, 0));
  EXPECT_NE(SceneDigest(cornell, 0), SceneDigest(moved, 0));
  EXPECT_NE(SceneDigest(cornell, 0), SceneDigest(LoadScene("cornell-zero-red"), 0));
  EXPECT_NE(FurnaceRequest().Description(1), FurnaceRequest().Description(2));
}

// The cache key is complete: each field of the request changed alone (a generated pair differing in one field)
// either leaves the image's bits as they were or changes the description, which keys the cache. The threads
// change nothing; every other field changes the image, so it must change the key (a cache that ignored the
// maximum depth would hand back an image traced to another depth). A field added to the request must be added
// here: the sizes below stop the build of this test until it is.
TEST(ConvergedReference, EveryFieldThatChangesTheImageChangesTheCacheKey) {
  static_assert(sizeof(TraceOptions) == 11 * sizeof(std::uint32_t), "a new TraceOptions field: add it below");
  static_assert(sizeof(ReferenceRequest) == sizeof(TraceOptions) + 2 * sizeof(std::uint32_t),
                "a new ReferenceRequest field: add it below");
  const Scene scene = LoadScene("cornell");
  ReferenceRequest base;
  base.trace.width = 8;
  base.trace.height = 6;
  base.trace.max_depth = 3;
  base.samples_per_pixel = 8;
  base.pass_samples = 2;
  const std::uint64_t digest = SceneDigest(scene, base.trace.frame);
  const ConvergedImage image = RenderConverged(scene, base);
  const std::pair<const char*, void (*)(ReferenceRequest&)> changes[] = {
      {"width", [](ReferenceRequest& r) { r.trace.width = 9; }},
      {"height", [](ReferenceRequest& r) { r.trace.height = 7; }},
      {"trace spp (each pass's, overridden)", [](ReferenceRequest& r) { r.trace.samples_per_pixel = 7; }},
      {"seed", [](ReferenceRequest& r) { r.trace.seed = 2; }},
      {"frame", [](ReferenceRequest& r) { r.trace.frame = 1; }},
      {"max depth", [](ReferenceRequest& r) { r.trace.max_depth = 2; }},
      {"filter bounce", [](ReferenceRequest& r) { r.trace.filter_bounce = 1; }},
      {"threads", [](ReferenceRequest& r) { r.trace.threads = 1; }},
      {"scattered", [](ReferenceRequest& r) { r.trace.scattered = true; }},
      {"filtered vertices", [](ReferenceRequest& r) { r.trace.scattered = true, r.trace.filtered_vertices = 2; }},
      // Kept paths add deeper records only: each pass is traced afresh, and its pixels are the records' own.
      {"continuation depth", [](ReferenceRequest& r) { r.trace.scattered = true, r.trace.continuation_depth = 3; }},
      {"spp", [](ReferenceRequest& r) { r.samples_per_pixel = 16; }},
      {"pass spp", [](ReferenceRequest& r) { r.pass_samples = 4; }},
  };
  for (const auto& [field, change] : changes) {
    ReferenceRequest changed = base;
    change(changed);
    const ConvergedImage other = RenderConverged(scene, changed);
    const bool same_image = SameBits(other.mean, image.mean) && SameBits(other.variance, image.variance);
    const bool same_key = changed.Description(digest) == base.Description(digest);
    std::printf("%-36s image %s, key %s\n", field, same_image ? "same" : "changed", same_key ? "same" : "changed");
    EXPECT_TRUE(same_image || !same_key) << field << " changes the image but not the key";
  }
}

}  // namespace
}  // namespace hpsf
