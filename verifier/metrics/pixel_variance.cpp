#include "verifier/metrics/pixel_variance.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/input_check.h"
#include "core/resolve.h"

namespace hpsf {
namespace {

constexpr std::uint32_t kNoGroup = 0xFFFFFFFFu;

glm::dvec3 D(glm::vec4 v) { return glm::dvec3(v.x, v.y, v.z); }

// The groups records actually used, numbered densely in the order of their first record, so that the
// per-group arrays scale with the cells used, not with a table's capacity.
struct Groups {
  std::vector<std::uint32_t> of_record;   // dense index, or kNoGroup
  std::vector<std::uint64_t> count;       // N_c
  std::vector<glm::dvec3> mean;           // m_c, the average contribution
  std::vector<glm::dvec3> mean_variance;  // s2_c / N_c, the variance of m_c
};

Groups CollectGroups(const RecordBatch& batch, std::span<const std::uint32_t> group_of_record,
                     std::size_t group_count) {
  Groups g;
  g.of_record.assign(batch.records.size(), kNoGroup);
  if (group_of_record.empty()) return g;
  std::vector<std::uint32_t> dense(group_count, kNoGroup);
  std::vector<glm::dvec3> sum;
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    const Record& r = batch.records[i];
    const std::uint32_t group = group_of_record[i];
    const bool placeable = shared::RecordHasVertex(r) && CheckRecordInputs(r) == InputVerdict::kAccepted;
    if (group >= group_count || !placeable) continue;
    if (dense[group] == kNoGroup) {
      dense[group] = std::uint32_t(g.count.size());
      g.count.push_back(0);
      sum.emplace_back(0.0);
    }
    const std::uint32_t c = g.of_record[i] = dense[group];
    ++g.count[c];
    sum[c] += D(r.contribution);
  }
  g.mean.resize(sum.size());
  for (std::size_t c = 0; c < sum.size(); ++c) g.mean[c] = sum[c] / double(g.count[c]);
  // Two passes: the squared deviations from the mean, not the difference of two large sums.
  std::vector<glm::dvec3> squares(sum.size(), glm::dvec3(0.0));
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    const std::uint32_t c = g.of_record[i];
    if (c == kNoGroup) continue;
    const glm::dvec3 deviation = D(batch.records[i].contribution) - g.mean[c];
    squares[c] += deviation * deviation;
  }
  g.mean_variance.resize(sum.size());
  for (std::size_t c = 0; c < sum.size(); ++c) {
    const double n = double(g.count[c]);
    g.mean_variance[c] = n > 1.0 ? squares[c] / (n - 1.0) / n : glm::dvec3(0.0);
  }
  return g;
}

glm::vec3 F(glm::dvec3 v) { return glm::vec3(v); }

// The sums over one band of tiles (tile_size rows of pixels) that make each tile's variance: S2_p / n, the pairs
// inside pixels, and per (tile, cell) T_Rc and A_Rc, gathered pixel by pixel and summed when the band is done, so
// that memory grows with one band's reads, not the image's.
class TileSums {
 public:
  TileSums(std::uint32_t width, std::uint32_t height, std::uint32_t tile_size)
      : width_(width),
        height_(height),
        tile_size_(tile_size),
        tiles_x_((width + tile_size - 1) / tile_size),
        tiles_((height + tile_size - 1) / tile_size * tiles_x_) {}

  std::size_t TileOf(std::size_t pixel) const {
    return pixel / width_ / tile_size_ * tiles_x_ + pixel % width_ / tile_size_;
  }
  void AddPixel(std::size_t tile, glm::dvec3 within, glm::dvec3 pairs) {
    tiles_[tile].within += within;
    tiles_[tile].pairs_in_pixels += pairs;
  }
  void AddReads(std::size_t tile, std::uint32_t group, glm::dvec3 throughput, glm::dvec3 squares) {
    band_.push_back({std::uint32_t(tile), group, throughput, squares});
  }
  // The band's pairs across pixels, once its last pixel is in.
  void EndBand(std::span<const glm::dvec3> mean_variance_of_group) {
    std::sort(band_.begin(), band_.end(),
              [](const Reads& a, const Reads& b) { return a.tile != b.tile ? a.tile < b.tile : a.group < b.group; });
    for (std::size_t k = 0; k < band_.size();) {
      const Reads& first = band_[k];
      glm::dvec3 t(0.0), a(0.0);
      for (; k < band_.size() && band_[k].tile == first.tile && band_[k].group == first.group; ++k) {
        t += band_[k].throughput;
        a += band_[k].squares;
      }
      tiles_[first.tile].pairs_across += (t * t - a) * mean_variance_of_group[first.group];
    }
    band_.clear();
  }
  // Var(M_R) per tile, K its pixels.
  Image Variances(std::size_t n) const {
    Image out(tiles_x_, std::uint32_t(tiles_.size() / tiles_x_));
    for (std::size_t r = 0; r < tiles_.size(); ++r) {
      const std::uint32_t tx = std::uint32_t(r % tiles_x_), ty = std::uint32_t(r / tiles_x_);
      const double k = double(std::min(tile_size_, width_ - tx * tile_size_)) *
                       double(std::min(tile_size_, height_ - ty * tile_size_));
      const Tile& tile = tiles_[r];
      const glm::dvec3 pairs = (n > 1 ? tile.pairs_in_pixels / double(n - 1) : glm::dvec3(0.0)) + tile.pairs_across;
      out.pixels[r] = F(tile.within / (k * k) + pairs / (double(n) * k * double(n) * k));
    }
    return out;
  }

 private:
  struct Tile {
    glm::dvec3 within{0.0}, pairs_in_pixels{0.0}, pairs_across{0.0};
  };
  struct Reads {
    std::uint32_t tile, group;
    glm::dvec3 throughput, squares;
  };
  std::uint32_t width_, height_, tile_size_, tiles_x_;
  std::vector<Tile> tiles_;
  std::vector<Reads> band_;
};

}  // namespace

std::string PixelVariance::ToString() const {
  double largest = 0.0;
  for (const glm::vec3& v : variance.pixels) largest = std::max({largest, double(v.x), double(v.y), double(v.z)});
  char text[256];
  std::snprintf(text, sizeof text,
                "[ PixelVariance %ux%u mean_variance: (%.6g, %.6g, %.6g) within pixels: (%.6g, %.6g, %.6g) "
                "largest pixel variance: %.6g ]",
                variance.width, variance.height, mean_variance.x, mean_variance.y, mean_variance.z, mean_within_pixel.x,
                mean_within_pixel.y, mean_within_pixel.z, largest);
  return text;
}

PixelVariance EstimatePixelVariance(const RecordBatch& batch, std::span<const std::uint32_t> group_of_record,
                                    std::size_t group_count, std::uint32_t tile_size) {
  CheckBatchShape(batch);
  if (tile_size == 0) throw std::invalid_argument("EstimatePixelVariance: a tile of 0 pixels");
  if (!group_of_record.empty() && group_of_record.size() != batch.records.size()) {
    throw std::invalid_argument("EstimatePixelVariance: " + std::to_string(group_of_record.size()) +
                                " group entries for " + std::to_string(batch.records.size()) + " records");
  }
  const Groups groups = CollectGroups(batch, group_of_record, group_count);
  const std::size_t n = batch.samples_per_pixel;
  const double pixels = double(batch.width) * double(batch.height);

  PixelVariance result;
  result.variance = result.within_pixel = Image(batch.width, batch.height);
  result.tile_size = tile_size;
  if (result.variance.pixels.empty()) return result;
  TileSums tiles(batch.width, batch.height, tile_size);
  // Per group over all samples: T_c, the throughput, and A_c, its squares, for the pairs across pixels.
  std::vector<glm::dvec3> throughput_of_group(groups.count.size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> squares_of_group(groups.count.size(), glm::dvec3(0.0));
  glm::dvec3 within_sum(0.0), pairs_in_pixels(0.0);
  std::vector<glm::dvec3> values(n);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> reads;  // (group, sample) of the pixel's grouped samples
  for (std::size_t pixel = 0; pixel < result.variance.pixels.size(); ++pixel) {
    const std::size_t tile = tiles.TileOf(pixel);
    glm::dvec3 mean(0.0);
    reads.clear();
    for (std::size_t s = 0; s < n; ++s) {
      const std::size_t i = pixel * n + s;
      const Record& r = batch.records[i];
      const std::uint32_t c = groups.of_record[i];
      if (CheckRecordInputs(r) != InputVerdict::kAccepted) {
        values[s] = glm::dvec3(0.0);
      } else {
        values[s] = AcceptedRecordValue(r, c == kNoGroup ? nullptr : &groups.mean[c]);
      }
      if (c != kNoGroup) reads.emplace_back(c, std::uint32_t(s));
      mean += values[s];
    }
    mean /= double(n);
    glm::dvec3 squares(0.0);
    for (std::size_t s = 0; s < n; ++s) squares += (values[s] - mean) * (values[s] - mean);
    const glm::dvec3 within = n > 1 ? squares / double(n - 1) / double(n) : glm::dvec3(0.0);
    within_sum += within;

    // The pixel's samples grouped by cell, in sample order within a cell: q_c (T_pc^2 - A_pc) is the covariance
    // of the distinct pairs of its samples that read cell c.
    std::sort(reads.begin(), reads.end());
    glm::dvec3 pairs(0.0);
    for (std::size_t k = 0; k < reads.size();) {
      const std::uint32_t c = reads[k].first;
      glm::dvec3 sum(0.0), sum_of_squares(0.0);
      for (; k < reads.size() && reads[k].first == c; ++k) {
        const glm::dvec3 t = D(batch.records[pixel * n + reads[k].second].throughput);
        sum += t;
        sum_of_squares += t * t;
      }
      throughput_of_group[c] += sum;
      squares_of_group[c] += sum_of_squares;
      pairs += (sum * sum - sum_of_squares) * groups.mean_variance[c];
      tiles.AddReads(tile, c, sum, sum_of_squares);
    }
    pairs_in_pixels += pairs;
    tiles.AddPixel(tile, within, pairs);
    const glm::dvec3 shared = n > 1 ? pairs / (double(n) * double(n - 1)) : glm::dvec3(0.0);
    result.within_pixel.pixels[pixel] = F(within);
    result.variance.pixels[pixel] = F(within + shared);
    const std::size_t row = pixel / batch.width;
    const bool row_done = pixel % batch.width == batch.width - 1;
    if (row_done && (row % tile_size == tile_size - 1 || row == batch.height - 1)) tiles.EndBand(groups.mean_variance);
  }
  result.tile_variance = tiles.Variances(n);

  result.mean_within_pixel = within_sum / (pixels * pixels);
  // Every pair of samples that read one cell, in one pixel or in two, is correlated by q_c; the pairs inside a
  // pixel also lowered its S2_p, which gives back their 1 / (n - 1) share.
  glm::dvec3 pairs(n > 1 ? pairs_in_pixels / double(n - 1) : glm::dvec3(0.0));
  for (std::size_t c = 0; c < groups.count.size(); ++c) {
    const glm::dvec3 t = throughput_of_group[c];
    pairs += (t * t - squares_of_group[c]) * groups.mean_variance[c];
  }
  const glm::dvec3 shared_mean = pairs / (double(n) * pixels * double(n) * pixels);
  result.mean_variance = result.mean_within_pixel + shared_mean;
  return result;
}

}  // namespace hpsf
