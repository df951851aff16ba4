#include "tools/hpsf/converged_reference.h"

#include <cstdio>
#include <vector>

#include "core/error.h"
#include "core/shared/rng.h"
#include "reference/reference_filter.h"

namespace hpsf {
namespace {

// The dimension the pass seeds are drawn in, apart from any the tracer or the filter uses.
constexpr std::uint32_t kPassSeedDimension = 0xFFFF0100u;
constexpr std::uint32_t kPassSeedPixel = 0xFFFFFFFFu;

std::uint32_t PassSeed(const ReferenceRequest& request, std::uint32_t pass) {
  return shared::RandomBits({request.trace.seed, request.trace.frame, kPassSeedPixel, pass, 0u}, kPassSeedDimension);
}

}  // namespace

void ReferenceRequest::Validate() const {
  trace.Validate();
  if (pass_samples == 0) throw ConfigError("--pass-spp", "must be at least 1");
  if (samples_per_pixel % pass_samples != 0 || samples_per_pixel / pass_samples < 2) {
    throw ConfigError("--spp", "must be a multiple of --pass-spp (" + std::to_string(pass_samples) +
                                   ") and at least twice it, for the variance from the passes; got " +
                                   std::to_string(samples_per_pixel));
  }
}

std::string ReferenceRequest::Description(std::uint64_t scene_digest) const {
  char digest[17];
  std::snprintf(digest, sizeof digest, "%016llx", static_cast<unsigned long long>(scene_digest));
  return std::string("scene digest ") + digest + "; tracer " + std::to_string(kTracerVersion) + "; " +
         std::to_string(trace.width) + "x" + std::to_string(trace.height) + " at " + std::to_string(samples_per_pixel) +
         " spp in passes of " + std::to_string(pass_samples) + "; seed " + std::to_string(trace.seed) + ", frame " +
         std::to_string(trace.frame) + ", max depth " + std::to_string(trace.max_depth) + ", filter bounce " +
         std::to_string(trace.filter_bounce) +
         (trace.scattered ? ", paths ending at the scattered vertex after " + std::to_string(trace.filtered_vertices) +
                                " filtered vertices"
                          : "");
}

ConvergedImage RenderConverged(const Scene& scene, const ReferenceRequest& request,
                               const std::function<void(std::uint32_t, std::uint32_t)>& progress) {
  request.Validate();
  const std::uint32_t passes = request.Passes();
  const std::size_t pixels = std::size_t(request.trace.width) * request.trace.height;
  // Welford's running mean and sum of squared deviations per pixel and channel, over the pass means, in pass order.
  std::vector<glm::dvec3> mean(pixels, glm::dvec3(0.0)), squares(pixels, glm::dvec3(0.0));
  const PreparedScene prepared(scene, request.trace.frame);  // every pass traces the same frame
  for (std::uint32_t p = 0; p < passes; ++p) {
    TraceOptions trace = request.trace;
    trace.samples_per_pixel = request.pass_samples;
    trace.seed = PassSeed(request, p);
    const Image pass = UnfilteredImage(TraceRecords(prepared, trace).batch);
    for (std::size_t i = 0; i < pixels; ++i) {
      const glm::dvec3 x(pass.pixels[i]);
      const glm::dvec3 delta = x - mean[i];
      mean[i] += delta / double(p + 1);
      squares[i] += delta * (x - mean[i]);
    }
    if (progress) progress(p + 1, passes);
  }
  ConvergedImage result{Image(request.trace.width, request.trace.height),
                        Image(request.trace.width, request.trace.height)};
  for (std::size_t i = 0; i < pixels; ++i) {
    result.mean.pixels[i] = glm::vec3(mean[i]);
    result.variance.pixels[i] = glm::vec3(squares[i] / (double(passes - 1) * double(passes)));
  }
  return result;
}

}  // namespace hpsf
