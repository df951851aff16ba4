// The error of an estimator split into bias and variance (Celarek et al. 2019, "Quantifying the error of light
// transport algorithms"), from K images of one configuration rendered with K independent seeds and a converged
// reference with its own per-pixel variance. Per value v (pixel and colour channel), with m_v the mean of the K
// images, s2_v their unbiased sample variance and r_v, q_v the reference and its variance:
//   MSE      = (1/K) sum_k mean_v (x_kv - r_v)^2
//   variance = mean_v s2_v                         (the estimator's noise)
//   bias^2   = mean_v [(m_v - r_v)^2 - s2_v / K - q_v]  (unbiased: the noise of m and of r taken out)
// so that MSE = bias^2 + variance + mean_v q_v exactly, up to rounding. bias^2 may come out slightly negative when
// the bias is below what K seeds resolve. Values not finite in any image are left out and counted. The same split
// of relMSE weighs each value's terms by w_v = 1 / (r_v^2 + 0.01), as relMSE weighs its squared error
// (verifier/metrics/image_metrics.h): relMSE = rel_bias2 + rel_variance + rel_reference_variance, so a few bright
// pixels do not hide what the filter does everywhere else.
#ifndef HPSF_VERIFIER_METRICS_ERROR_SPLIT_H
#define HPSF_VERIFIER_METRICS_ERROR_SPLIT_H

#include <cstdint>
#include <span>

#include "core/image.h"

namespace hpsf {

struct ErrorSplit {
  double mse = 0.0, bias2 = 0.0, variance = 0.0;
  // The standard error of bias2 from the spread of its per-value terms (values taken as independent, which
  // neighbouring pixels of a filtered image are not quite): a bias2 within about two of it is no bias resolved.
  double bias2_standard_error = 0.0;
  double reference_variance = 0.0;                                                         // mean_v q_v
  double relmse = 0.0, rel_bias2 = 0.0, rel_variance = 0.0, rel_reference_variance = 0.0;  // weighted by w_v
  // The bias of the image mean: the mean over the K images of (image mean - reference mean), and its standard error
  // from the spread of those K differences and the reference mean's own variance (sum_v q_v / n^2). An image-wide
  // statistic, so the correlation between neighbouring pixels of a filtered image is in its spread: the test of
  // "no bias" a furnace must pass (|mean_error| within a few standard errors).
  double mean_error = 0.0, mean_error_standard_error = 0.0;
  std::uint64_t values = 0, nonfinite = 0;
};

// At least two images, all the reference's size; reference_variance may be empty (taken as 0). An
// std::invalid_argument otherwise.
ErrorSplit SplitError(std::span<const Image> images, const Image& reference, const Image* reference_variance);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_ERROR_SPLIT_H
