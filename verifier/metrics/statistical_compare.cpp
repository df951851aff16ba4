#include "verifier/metrics/statistical_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

#include "core/error.h"
#include "verifier/theory/chi_square.h"

namespace hpsf {
namespace {

constexpr int kMeanTests = 3;

// |z| beyond which a two-sided normal test rejects at `level`, taken as a complement so that tiny levels keep
// their digits.
double TwoSidedThreshold(double level) {
  return boost::math::quantile(boost::math::complement(boost::math::normal(), level / 2.0));
}

// One image's estimate of a mean (a tile's or the image's): the value, its variance, the variance's degrees of
// freedom, and the image's samples per pixel.
struct Estimate {
  double mean, variance, dof, spp;
};

// The image of fewer samples per pixel gets at least the other's variance scaled to its own samples (and then the
// other's degrees of freedom). Under H0 two renders of one renderer have one variance per sample; a render of few
// samples that missed the rare bright ones (the light found by a diffuse bounce) has a mean too low and a variance
// too small at once, which Welch's t, taking the variance as it comes, makes a false alarm of against a precise
// image (measured: 43% of pairs at 4 against 256 spp, alpha 0.01). The precise image's variance, scaled, does not
// miss them, and rests on more samples: the floored variance takes the precise image's degrees of freedom. Two
// images of equal spp are skewed alike, their difference is not, and neither is floored. This assumes one renderer
// at two sample counts (the golden use); where the noisier per sample is the precise image, the floor is larger
// than the truth and the test conservative.
Estimate Floored(const Estimate& e, const Estimate& other) {
  if (!(e.spp < other.spp)) return e;
  const double scaled = other.variance * (other.spp / e.spp);
  return scaled > e.variance ? Estimate{e.mean, scaled, other.dof, e.spp} : e;
}

// Welch's test of two means, each variance estimated on its degrees of freedom, after the floor.
TileT Welch(const Estimate& a_in, const Estimate& b_in) {
  const Estimate a = Floored(a_in, b_in), b = Floored(b_in, a_in);
  const double ma = a.mean, mb = b.mean, va = a.variance, vb = b.variance, nu_a = a.dof, nu_b = b.dof;
  TileT r;
  const double sum = va + vb;
  if (sum == 0.0) {  // no noise: equal passes, any difference rejects
    r.t = ma == mb ? 0.0 : (ma - mb) * std::numeric_limits<double>::infinity();
  } else {
    r.t = (ma - mb) / std::sqrt(sum);
  }
  const double spread = (va > 0.0 ? va * va / nu_a : 0.0) + (vb > 0.0 ? vb * vb / nu_b : 0.0);
  r.dof = spread > 0.0 ? sum * sum / spread : std::numeric_limits<double>::infinity();
  if (std::isnan(r.t)) {
    r.p = std::numeric_limits<double>::quiet_NaN();
  } else if (std::isinf(r.t)) {
    r.p = 0.0;
  } else if (std::isinf(r.dof)) {
    r.p = 2.0 * boost::math::cdf(boost::math::complement(boost::math::normal(), std::abs(r.t)));
  } else {
    r.p = 2.0 * boost::math::cdf(boost::math::complement(boost::math::students_t(r.dof), std::abs(r.t)));
  }
  return r;
}

// A NaN compares false, so it rejects.
bool Passes(const TileT& test, double level) { return test.p >= level; }

// Smaller p first, NaN before everything, so the worst test names a NaN input first.
bool Worse(const TileT& test, const TileT& than) {
  return std::isnan(test.p) ? !std::isnan(than.p) : !std::isnan(than.p) && test.p < than.p;
}

glm::dvec3 ImageMean(const Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& v : image.pixels) sum += glm::dvec3(v);
  return image.pixels.empty() ? sum : sum / double(image.pixels.size());
}

glm::dvec3 TileMean(const Image& image, std::uint32_t x0, std::uint32_t y0, std::uint32_t size) {
  glm::dvec3 sum(0.0);
  const std::uint32_t x1 = std::min(image.width, x0 + size), y1 = std::min(image.height, y0 + size);
  for (std::uint32_t y = y0; y < y1; ++y) {
    for (std::uint32_t x = x0; x < x1; ++x) sum += glm::dvec3(image.pixels[std::size_t(y) * image.width + x]);
  }
  return sum / double(std::size_t(x1 - x0) * (y1 - y0));
}

std::string Size(const Image& image) { return std::to_string(image.width) + "x" + std::to_string(image.height); }

std::uint32_t Tiles(std::uint32_t pixels, std::uint32_t tile) { return (pixels + tile - 1) / tile; }

// A variance read from a file is a count of noise: finite and not negative, or the file is bad input.
void RequireVariance(float v, const std::string& source, const std::string& what, std::size_t x, std::size_t y, int c) {
  if (!(v >= 0.0f) || std::isinf(v)) {
    throw InputError(source + ": " + what + " at (" + std::to_string(x) + ", " + std::to_string(y) + ", " + "RGB"[c] +
                     ") is " + std::to_string(v) + ", not a finite variance");
  }
}

std::uint32_t PositiveInteger(const ChannelImage& image, const char* key, const char* hint) {
  const auto found = image.metadata.find(key);
  unsigned long value = 0;
  char rest = 0;
  if (found == image.metadata.end() || std::sscanf(found->second.c_str(), "%lu%c", &value, &rest) != 1 || value == 0 ||
      value > 0xFFFFFFFFul) {
    throw InputError(image.path + ": no attribute 'hpsf:" + key + "' holding a positive whole number" + hint);
  }
  return std::uint32_t(value);
}

}  // namespace

std::string StatisticalComparison::ToString() const {
  char text[640];
  std::snprintf(text, sizeof text,
                "%s at alpha %.3g (Welch t-tests): tiles of %ux%u %llu tested, %llu rejected (p < %.3g), worst tile "
                "(%u, %u, %c) t %.3g on %.4g dof, p %.3g; image mean t (%.3g, %.3g, %.3g), p (%.3g, %.3g, %.3g), "
                "rejects below %.3g",
                consistent ? "consistent with noise" : "NOT consistent with noise", alpha, tile_size, tile_size,
                static_cast<unsigned long long>(tiles_tested), static_cast<unsigned long long>(tiles_rejected),
                tile_level, worst.x, worst.y, "RGB"[worst.channel], worst.t, worst.dof, worst.p, mean[0].t, mean[1].t,
                mean[2].t, mean[0].p, mean[1].p, mean[2].p, mean_level);
  return text;
}

NoisyImage MakeNoisyImage(std::string source, const Image& mean, const PixelVariance& variance,
                          std::uint32_t samples_per_pixel) {
  return {std::move(source),     mean, variance.variance, variance.tile_variance, variance.tile_size, samples_per_pixel,
          variance.mean_variance};
}

NoisyImage ToNoisyImage(const ChannelImage& image) {
  const char* const names[9] = {
      "R", "G", "B", "variance.R", "variance.G", "variance.B", "tile_variance.R", "tile_variance.G", "tile_variance.B"};
  int index[9];
  for (int k = 0; k < 9; ++k) {
    index[k] = image.ChannelIndex(names[k]);
    if (index[k] < 0) {
      throw InputError(image.path + ": no channel '" + names[k] + "'" +
                       (k >= 3 ? " (render it with --variance, by this version of hpsf)" : ""));
    }
  }
  NoisyImage noisy;
  noisy.source = image.path;
  const auto found = image.metadata.find("mean_variance");
  if (found == image.metadata.end() || std::sscanf(found->second.c_str(), "%lf %lf %lf", &noisy.mean_variance.x,
                                                   &noisy.mean_variance.y, &noisy.mean_variance.z) != 3) {
    throw InputError(image.path + ": no attribute 'hpsf:mean_variance' of three numbers (render it with --variance)");
  }
  for (int c = 0; c < 3; ++c) {
    if (!(noisy.mean_variance[c] >= 0.0) || std::isinf(noisy.mean_variance[c])) {
      throw InputError(image.path + ": 'hpsf:mean_variance' holds " + std::to_string(noisy.mean_variance[c]) +
                       ", not a finite variance");
    }
  }
  noisy.samples_per_pixel = PositiveInteger(image, "spp", " (render it with --variance)");
  noisy.tile_size = PositiveInteger(image, "variance_tile", " (render it with --variance, by this version of hpsf)");
  const std::uint32_t width = std::uint32_t(image.width), height = std::uint32_t(image.height);
  noisy.mean = noisy.variance = Image(width, height);
  noisy.tile_variance = Image(Tiles(width, noisy.tile_size), Tiles(height, noisy.tile_size));
  for (std::size_t p = 0; p < image.PixelCount(); ++p) {
    const std::size_t x = p % width, y = p / width;
    for (int c = 0; c < 3; ++c) {
      noisy.mean.pixels[p][c] = image.At(p, index[c]);
      noisy.variance.pixels[p][c] = image.At(p, index[3 + c]);
      RequireVariance(noisy.variance.pixels[p][c], image.path, "variance", x, y, c);
      // Every pixel of a tile holds the tile's variance; the tile's top-left one is read.
      if (x % noisy.tile_size == 0 && y % noisy.tile_size == 0) {
        const float v = image.At(p, index[6 + c]);
        RequireVariance(v, image.path, "tile_variance", x, y, c);
        noisy.tile_variance.pixels[(y / noisy.tile_size) * noisy.tile_variance.width + x / noisy.tile_size][c] = v;
      }
    }
  }
  return noisy;
}

nlohmann::json ToJson(const StatisticalComparison& c) {
  auto number = [](double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf");
  };
  auto test = [&](const TileT& t) {
    return nlohmann::json{{"t", number(t.t)}, {"dof", number(t.dof)}, {"p", number(t.p)}};
  };
  nlohmann::json worst = test(c.worst);
  worst["x"] = c.worst.x;
  worst["y"] = c.worst.y;
  worst["channel"] = std::string(1, "RGB"[c.worst.channel]);
  return {{"alpha", c.alpha},
          {"test", "welch"},
          {"tile_size", c.tile_size},
          {"tiles_tested", c.tiles_tested},
          {"tiles_rejected", c.tiles_rejected},
          {"tile_level", c.tile_level},
          {"worst_tile", worst},
          {"image_mean", {test(c.mean[0]), test(c.mean[1]), test(c.mean[2])}},
          {"mean_level", c.mean_level},
          {"consistent_with_noise", c.consistent}};
}

StatisticalComparison CompareStatistically(const NoisyImage& a, const NoisyImage& b, double alpha,
                                           std::uint32_t minimum_spp) {
  if (!(alpha > 0.0 && alpha < 1.0)) throw InputError("alpha: the significance level must lie in (0, 1)");
  for (const NoisyImage* image : {&a, &b}) {
    if (image->variance.width != image->mean.width || image->variance.height != image->mean.height ||
        image->tile_size == 0 || image->tile_variance.width != Tiles(image->mean.width, image->tile_size) ||
        image->tile_variance.height != Tiles(image->mean.height, image->tile_size)) {
      throw InputError(image->source + ": its variances do not cover its " + Size(image->mean) + " pixels");
    }
    if (image->samples_per_pixel < std::max(minimum_spp, 2u)) {
      throw InputError(image->source + ": " + std::to_string(image->samples_per_pixel) +
                       " samples per pixel; the statistical comparison holds its false-alarm rate from " +
                       std::to_string(kMinimumStatisticalSpp) + " spp on (render it with --spp " +
                       std::to_string(kMinimumStatisticalSpp) + " or more)");
    }
  }
  if (b.mean.width != a.mean.width || b.mean.height != a.mean.height) {
    throw InputError(b.source + " is " + Size(b.mean) + ", " + a.source + " " + Size(a.mean));
  }
  if (b.tile_size != a.tile_size) {
    throw InputError(b.source + " has variance tiles of " + std::to_string(b.tile_size) + " pixels, " + a.source +
                     " of " + std::to_string(a.tile_size));
  }
  StatisticalComparison result;
  result.alpha = alpha;
  result.tile_size = a.tile_size;
  const std::uint32_t size = a.tile_size;
  const double spp_a = a.samples_per_pixel, spp_b = b.samples_per_pixel;
  const std::size_t tiles = a.tile_variance.pixels.size();
  // Each family gets alpha / 2: the two together wrongly reject a consistent pair with probability <= alpha.
  result.tile_level = SidakLevel(alpha / 2.0, int(3 * tiles));
  result.mean_level = SidakLevel(alpha / 2.0, kMeanTests);
  result.tiles_tested = tiles;
  result.worst.p = 2.0;  // any test is worse
  for (std::uint32_t ty = 0; ty < a.tile_variance.height; ++ty) {
    for (std::uint32_t tx = 0; tx < a.tile_variance.width; ++tx) {
      const std::uint32_t x = tx * size, y = ty * size;
      const double k = double(std::min(size, a.mean.width - x)) * double(std::min(size, a.mean.height - y));
      const glm::dvec3 mean_a = TileMean(a.mean, x, y, size), mean_b = TileMean(b.mean, x, y, size);
      const std::size_t r = std::size_t(ty) * a.tile_variance.width + tx;
      bool rejected = false;
      for (int c = 0; c < 3; ++c) {
        TileT test = Welch({mean_a[c], a.tile_variance.pixels[r][c], k * double(a.samples_per_pixel - 1), spp_a},
                           {mean_b[c], b.tile_variance.pixels[r][c], k * double(b.samples_per_pixel - 1), spp_b});
        test.x = x;
        test.y = y;
        test.channel = c;
        rejected = rejected || !Passes(test, result.tile_level);
        if (Worse(test, result.worst)) result.worst = test;
      }
      result.tiles_rejected += rejected;
    }
  }
  const double pixels = double(a.mean.pixels.size());
  const glm::dvec3 mean_a = ImageMean(a.mean), mean_b = ImageMean(b.mean);
  bool means_pass = true;
  for (int c = 0; c < 3; ++c) {
    result.mean[c] = Welch({mean_a[c], a.mean_variance[c], pixels * double(a.samples_per_pixel - 1), spp_a},
                           {mean_b[c], b.mean_variance[c], pixels * double(b.samples_per_pixel - 1), spp_b});
    result.mean[c].channel = c;
    means_pass = means_pass && Passes(result.mean[c], result.mean_level);
  }
  result.consistent = result.tiles_rejected == 0 && means_pass;
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
