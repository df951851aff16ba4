#include "verifier/metrics/error_split.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace hpsf {

ErrorSplit SplitError(std::span<const Image> images, const Image& reference, const Image* reference_variance) {
  if (images.size() < 2) throw std::invalid_argument("SplitError: the variance needs two images or more");
  for (const Image& image : images) {
    if (image.width != reference.width || image.height != reference.height) {
      throw std::invalid_argument("SplitError: an image of another size than the reference");
    }
  }
  const double k = double(images.size());
  ErrorSplit split;
  double mse = 0.0, bias2 = 0.0, bias2_squares = 0.0, variance = 0.0, reference_noise = 0.0, reference_sum = 0.0;
  double relmse = 0.0, rel_bias2 = 0.0, rel_variance = 0.0, rel_reference_noise = 0.0;
  std::vector<double> image_sums(images.size(), 0.0);
  for (std::size_t p = 0; p < reference.pixels.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      const double r = reference.pixels[p][c];
      const double q = reference_variance ? double(reference_variance->pixels[p][c]) : 0.0;
      bool finite = std::isfinite(r) && std::isfinite(q);
      double sum = 0.0, squares = 0.0;
      for (const Image& image : images) {
        const double x = image.pixels[p][c];
        finite = finite && std::isfinite(x);
        sum += x;
        squares += (x - r) * (x - r);
      }
      if (!finite) {
        ++split.nonfinite;
        continue;
      }
      const double m = sum / k;
      double deviations = 0.0;
      for (const Image& image : images) deviations += (image.pixels[p][c] - m) * (image.pixels[p][c] - m);
      const double s2 = deviations / (k - 1.0);
      mse += squares / k;
      variance += s2;
      const double term = (m - r) * (m - r) - s2 / k - q;
      bias2 += term;
      bias2_squares += term * term;
      reference_noise += q;
      reference_sum += r;
      const double w = 1.0 / (r * r + 0.01);
      relmse += w * squares / k;
      rel_bias2 += w * term;
      rel_variance += w * s2;
      rel_reference_noise += w * q;
      for (std::size_t i = 0; i < images.size(); ++i) image_sums[i] += images[i].pixels[p][c];
      ++split.values;
    }
  }
  if (split.values > 0) {
    const double n = double(split.values);
    split.mse = mse / n;
    split.bias2 = bias2 / n;
    if (n > 1.0) {
      split.bias2_standard_error =
          std::sqrt(std::max(0.0, (bias2_squares - n * split.bias2 * split.bias2) / (n - 1.0)) / n);
    }
    split.variance = variance / n;
    split.reference_variance = reference_noise / n;
    split.relmse = relmse / n;
    split.rel_bias2 = rel_bias2 / n;
    split.rel_variance = rel_variance / n;
    split.rel_reference_variance = rel_reference_noise / n;
    double errors = 0.0, error_squares = 0.0;
    for (const double sum : image_sums) {
      const double e = (sum - reference_sum) / n;
      errors += e;
      error_squares += e * e;
    }
    split.mean_error = errors / k;
    const double spread = std::max(0.0, (error_squares - k * split.mean_error * split.mean_error) / (k - 1.0));
    split.mean_error_standard_error = std::sqrt(spread / k + reference_noise / (n * n));
  }
  return split;
}

}  // namespace hpsf
