// The variance of each filtered pixel, so that two renders can be compared against their noise instead of a
// fixed tolerance (`hpsf render --variance`, `hpsf diff --statistical`).
//
// A pixel P_p is the mean of its n records' values v_s = radiance_before + throughput t_s * m_c (core/resolve.h),
// m_c the average contribution of the record's cell c (its own contribution without one). Records are
// independent draws, but a cell's average is shared by every sample that reads it, in this pixel and others.
// Treating the cell assignment as fixed (a linearisation: which records land in which cell is itself random, and
// the noise of a cell's records is taken as that of independent draws from one distribution), two samples are
// correlated only when they read the same cell, Cov(v_s, v_s') = t_s t_s' q_c with q_c = s2_c / N_c: N_c the
// records in cell c, s2_c the unbiased sample variance of their contributions (0 when N_c == 1). Then
//   Var(P_p) = (1/n^2) [sum_s Var(v_s) + sum_{s != s'} Cov(v_s, v_s')]
// and the within-pixel sample variance S2_p (unbiased, over the n values v_s) has the expectation
// (1/n) sum_s Var(v_s) - sum_{s != s'} Cov / (n (n - 1)), so per channel
//   Var(P_p) ~= S2_p / n + sum_c q_c (T_pc^2 - A_pc) / (n (n - 1)),
// T_pc and A_pc the sum of t_s and of t_s^2 over the pixel's samples reading c. Only pairs of distinct samples
// sharing a cell add to S2_p / n: the noise of a cell read by one sample of the pixel already shows in S2_p.
// (The plainer S2_p / n + sum_c W_pc^2 q_c, W_pc = T_pc / n, counts that noise twice: measured on the Cornell
// box, 32x32 at 16 spp, it is about 20% high on a typical filtered pixel; this estimate is within 4%.)
// The image mean (1/P) sum_p P_p, whose test has the power against a small bias, gets every pair of samples
// that read one cell, in one pixel or in two, T_c and A_c summed over all samples reading c:
//   Var ~= (1/P^2) sum_p S2_p / n + (1/(n P))^2 [sum_p sum_c q_c (T_pc^2 - A_pc) / (n - 1) + sum_c q_c (T_c^2 - A_c)].
// Any square tile R of K pixels is the same sum over R's pixels and the pairs of R's samples that read one cell
// (T_Rc and A_Rc summed over R):
//   Var(M_R) ~= (1/K^2) sum_p S2_p / n + (1/(n K))^2 [sum_p sum_c q_c (T_pc^2 - A_pc) / (n - 1) + sum_c q_c (T_Rc^2 -
//   A_Rc)],
// which is the image mean's for one tile over the whole image and the pixel's for tiles of one pixel. The
// statistical comparison tests tiles, not pixels: a pixel's S2_p rests on n samples, so at a few spp it often
// misses most of the pixel's noise (all n samples jittered into one cell, none into its neighbour), while a tile's
// rests on K (n - 1) degrees of freedom.
// S2_p needs two samples: with one it is 0 and the estimate is meaningless, so the command line refuses --variance
// below 2 samples per pixel.
#ifndef HPSF_VERIFIER_METRICS_PIXEL_VARIANCE_H
#define HPSF_VERIFIER_METRICS_PIXEL_VARIANCE_H

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include <glm/vec3.hpp>

#include "core/image.h"
#include "core/record.h"

namespace hpsf {

// The tiles' edge in pixels: 8 holds 64 pixels, so 64 (n - 1) degrees of freedom a tile at n spp, and still
// tells a wrong region of an image from a wrong image.
constexpr std::uint32_t kVarianceTile = 8;

struct PixelVariance {
  Image variance;                 // Var(P_p) per pixel and channel
  glm::dvec3 mean_variance{0.0};  // the variance of the image mean, per channel
  // The variance of each tile's mean, tiles of tile_size pixels a side from the top left (those of the last row and
  // column smaller where the size does not divide), one texel a tile: ceil(W / tile_size) x ceil(H / tile_size).
  Image tile_variance;
  std::uint32_t tile_size = kVarianceTile;
  // The within-pixel term alone (S2_p / n, and its share of the image mean's variance): the naive estimate,
  // kept to show how much of the noise comes from cells shared between pixels.
  Image within_pixel;
  glm::dvec3 mean_within_pixel{0.0};
  std::string ToString() const;
};

// group_of_record[i]: the cell or table slot whose average record i's value used, or any value >= group_count
// when it used none (no vertex, unkeyable, probe failure, rejected). An empty span means no record used a
// group: the unfiltered image, whose variance is S2_p / n alone. A rejected record's value is 0 (it still counts
// in its pixel's n); neither it nor a record without a vertex joins a group, whatever its entry says, as no
// backend places them. Sequential in double, so no bit depends on the machine's threads.
PixelVariance EstimatePixelVariance(const RecordBatch& batch, std::span<const std::uint32_t> group_of_record,
                                    std::size_t group_count, std::uint32_t tile_size = kVarianceTile);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_PIXEL_VARIANCE_H
