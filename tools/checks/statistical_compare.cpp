#include "tools/checks/statistical_compare.h"

#include <cmath>
#include <cstdio>

#include <boost/math/distributions/normal.hpp>

#include "core/error.h"
#include "tools/checks/chi_square.h"

namespace hpsf {
namespace {

constexpr int kMeanTests = 3;

// |z| beyond which a two-sided test rejects at `level`: the upper level / 2 quantile of the standard normal,
// taken as a complement so that tiny levels keep their digits.
double TwoSidedThreshold(double level) {
  return boost::math::quantile(boost::math::complement(boost::math::normal(), level / 2.0));
}

double Z(double a, double b, double variance_sum) {
  if (variance_sum == 0.0 && a == b) return 0.0;  // no noise and no difference
  return (a - b) / std::sqrt(variance_sum);       // +-inf for a difference without noise, NaN for a NaN input
}

// A NaN compares false, so it rejects.
bool Passes(double z, double threshold) { return std::abs(z) <= threshold; }

// |z| ordered with NaN above everything, so the worst test names a NaN input first.
bool Worse(double z, double than) { return std::isnan(z) ? !std::isnan(than) : std::abs(z) > std::abs(than); }

glm::dvec3 ImageMean(const Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& v : image.pixels) sum += glm::dvec3(v);
  return image.pixels.empty() ? sum : sum / double(image.pixels.size());
}

void RequireSize(const Image& image, const Image& like, const char* what) {
  if (image.width != like.width || image.height != like.height) {
    throw InputError(std::string(what) + " is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                     ", the image " + std::to_string(like.width) + "x" + std::to_string(like.height));
  }
}

}  // namespace

std::string StatisticalComparison::ToString() const {
  char text[512];
  std::snprintf(text, sizeof text,
                "%s at alpha %.3g: pixels %llu tested, %llu rejected (|z| > %.3f), worst (%u, %u, %c) z %.3g; "
                "image mean z (%.3g, %.3g, %.3g), threshold %.3f",
                consistent ? "consistent with noise" : "NOT consistent with noise", alpha,
                static_cast<unsigned long long>(pixels_tested), static_cast<unsigned long long>(pixels_rejected),
                pixel_threshold, worst.x, worst.y, "RGB"[worst.channel], worst.z, mean_z.x, mean_z.y, mean_z.z,
                mean_threshold);
  return text;
}

NoisyImage ToNoisyImage(const ChannelImage& image) {
  const char* const names[6] = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
  int index[6];
  for (int k = 0; k < 6; ++k) {
    index[k] = image.ChannelIndex(names[k]);
    if (index[k] < 0) {
      throw InputError(image.path + ": no channel '" + names[k] + "'" + (k >= 3 ? " (render it with --variance)" : ""));
    }
  }
  NoisyImage noisy;
  const auto found = image.metadata.find("mean_variance");
  if (found == image.metadata.end() || std::sscanf(found->second.c_str(), "%lf %lf %lf", &noisy.mean_variance.x,
                                                   &noisy.mean_variance.y, &noisy.mean_variance.z) != 3) {
    throw InputError(image.path + ": no attribute 'hpsf:mean_variance' of three numbers (render it with --variance)");
  }
  noisy.mean = noisy.variance = Image(std::uint32_t(image.width), std::uint32_t(image.height));
  for (std::size_t p = 0; p < image.PixelCount(); ++p) {
    noisy.mean.pixels[p] = glm::vec3(image.At(p, index[0]), image.At(p, index[1]), image.At(p, index[2]));
    noisy.variance.pixels[p] = glm::vec3(image.At(p, index[3]), image.At(p, index[4]), image.At(p, index[5]));
  }
  return noisy;
}

nlohmann::json ToJson(const StatisticalComparison& c) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(v > 0 ? "inf" : "nan"); };
  return {{"alpha", c.alpha},
          {"pixels_tested", c.pixels_tested},
          {"pixels_rejected", c.pixels_rejected},
          {"pixel_threshold", c.pixel_threshold},
          {"worst_pixel",
           {{"x", c.worst.x}, {"y", c.worst.y}, {"channel", "RGB"[c.worst.channel]}, {"z", number(c.worst.z)}}},
          {"mean_z", {number(c.mean_z.x), number(c.mean_z.y), number(c.mean_z.z)}},
          {"mean_threshold", c.mean_threshold},
          {"consistent_with_noise", c.consistent}};
}

StatisticalComparison CompareStatistically(const NoisyImage& a, const NoisyImage& b, double alpha) {
  RequireSize(a.variance, a.mean, "the first image's variance");
  RequireSize(b.variance, b.mean, "the second image's variance");
  RequireSize(b.mean, a.mean, "the second image");
  if (!(alpha > 0.0 && alpha < 1.0)) throw InputError("alpha: the significance level must lie in (0, 1)");
  StatisticalComparison result;
  result.alpha = alpha;
  const std::size_t pixels = a.mean.pixels.size();
  // Each family gets alpha / 2: the two together wrongly reject a consistent pair with probability <= alpha.
  result.pixel_threshold = TwoSidedThreshold(SidakLevel(alpha / 2.0, int(3 * pixels)));
  result.mean_threshold = TwoSidedThreshold(SidakLevel(alpha / 2.0, kMeanTests));
  result.pixels_tested = pixels;
  for (std::size_t p = 0; p < pixels; ++p) {
    bool rejected = false;
    for (int c = 0; c < 3; ++c) {
      const double z = Z(a.mean.pixels[p][c], b.mean.pixels[p][c],
                         double(a.variance.pixels[p][c]) + double(b.variance.pixels[p][c]));
      rejected = rejected || !Passes(z, result.pixel_threshold);
      if ((p == 0 && c == 0) || Worse(z, result.worst.z)) {
        result.worst = {std::uint32_t(p % a.mean.width), std::uint32_t(p / a.mean.width), c, z};
      }
    }
    result.pixels_rejected += rejected;
  }
  const glm::dvec3 mean_a = ImageMean(a.mean), mean_b = ImageMean(b.mean);
  bool means_pass = true;
  for (int c = 0; c < 3; ++c) {
    result.mean_z[c] = Z(mean_a[c], mean_b[c], a.mean_variance[c] + b.mean_variance[c]);
    means_pass = means_pass && Passes(result.mean_z[c], result.mean_threshold);
  }
  result.consistent = result.pixels_rejected == 0 && means_pass;
  return result;
}

double MeanTestPower(double bias, double sigma, double alpha) {
  if (!(sigma > 0.0)) return bias != 0.0 ? 1.0 : 0.0;  // no noise: any difference is seen, none is not
  const double t = TwoSidedThreshold(SidakLevel(alpha / 2.0, kMeanTests));
  const double shift = std::abs(bias) / sigma;
  const boost::math::normal normal;
  return boost::math::cdf(boost::math::complement(normal, t - shift)) + boost::math::cdf(normal, -t - shift);
}

}  // namespace hpsf
