#include "verifier/theory/jitter_statistics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <boost/math/distributions/chi_squared.hpp>

#include "core/filter_config.h"

namespace hpsf {
namespace {

// The square, mean and pair tests: cells of 2^-6 and a jitter of 64 cells, so a record at the origin lands in
// cell floor(64 (2u - 1)) of each tangent axis, [-64, 64): the offset read to 7 bits, every bin equally likely.
constexpr int kOffsetCells = 128;
// The kernel and level tests: unit jitter, as renderers run it.
constexpr float kLevelFootprint = 1.0f / 64.0f;  // w = d / 64: levels change at d = 64 * 2^l
constexpr double kLevelNearest = 62.0, kLevelFarthest = 130.0;

const glm::vec3 kX(1.0f, 0.0f, 0.0f), kY(0.0f, 1.0f, 0.0f), kZ(0.0f, 0.0f, 1.0f);

KeyParams BaseParams(std::uint32_t seed, std::uint32_t frame, std::uint32_t count) {
  FilterConfig config;
  config.lod = false;
  config.cell_size = 1.0f;
  config.jitter_scale = 1.0f;
  config.normal.mode = NormalMode::kNone;
  config.seed = seed;
  config.frame = frame;
  return MakeKeyParams(config, 1.0f, count);
}

// A record at `position` whose jitter moves it along `tangent` (u1) and `bitangent` (u2).
Record JitterRecord(std::uint32_t pixel, std::uint32_t sample, std::uint32_t bounce, glm::vec3 position,
                    glm::vec3 normal, glm::vec3 tangent, glm::vec3 bitangent, glm::vec3 previous) {
  VertexSample v;
  v.pixel = pixel;
  v.sample = sample;
  v.bounce = bounce;
  v.position = position;
  v.normal = normal;
  v.previous = previous;
  v.contribution = v.throughput = glm::vec3(0.5f);
  Record r = MakeVertexRecord(v);
  r.tangent = glm::vec4(tangent, 0.0f);
  r.bitangent = glm::vec4(bitangent, 0.0f);
  return r;
}

Record OffsetRecord(std::uint32_t pixel, std::uint32_t sample, std::uint32_t bounce) {
  return JitterRecord(pixel, sample, bounce, glm::vec3(0.0f), kZ, kX, kY, -kZ);
}

// The offset bin of a cell coordinate, `bins` per axis, or -1 outside [-64, 64).
int OffsetBin(std::uint32_t cell_word, int bins) {
  const int cell = int(cell_word);
  if (cell < -kOffsetCells / 2 || cell >= kOffsetCells / 2) return -1;
  return (cell + kOffsetCells / 2) / (kOffsetCells / bins);
}

std::vector<double> Uniform(std::size_t cells) {
  std::vector<double> p(cells + 1, 1.0 / double(cells));
  p.back() = 0.0;  // the last cell: outside every bin, impossible
  return p;
}

// P(l' - l = -1, 0, +1) for a record at distance z at grazing incidence, its level l and jitter amplitude 2^l.
std::vector<double> LevelChangeProbabilities(double z, int level) {
  const double amplitude = std::ldexp(1.0, level);
  const double lower = std::ldexp(1.0, level) / kLevelFootprint, upper = 2.0 * lower;
  const double down = std::clamp((lower - (z - amplitude)) / (2.0 * amplitude), 0.0, 1.0);
  const double up = std::clamp((z + amplitude - upper) / (2.0 * amplitude), 0.0, 1.0);
  return {down, 1.0 - down - up, up, 0.0};
}

int LevelBefore(const Record& r, const KeyParams& p) {
  const float d = shared::PathLength(r.position.w, glm::vec3(r.position), glm::vec3(r.previous));
  return shared::LevelOfDetail(p.footprint_scale, d, p.level_min, p.level_max);
}

}  // namespace

std::vector<KeyResult> CoreKeyPass(std::span<const Record> records, const KeyParams& params) {
  return ComputeKeys(records, params);
}

const char* ToString(JitterTest test) {
  switch (test) {
    case JitterTest::kSquare:
      return "square";
    case JitterTest::kMean:
      return "mean";
    case JitterTest::kPixelPairs:
      return "pixel pairs";
    case JitterTest::kSamplePairs:
      return "sample pairs";
    case JitterTest::kBouncePairs:
      return "bounce pairs";
    case JitterTest::kKernel:
      return "kernel";
    case JitterTest::kLevelChange:
      return "level change";
  }
  return "?";
}

JitterExperiment MakeJitterExperiment(JitterTest test, std::uint32_t seed, std::uint32_t frame, std::uint32_t samples) {
  if (samples == 0) throw std::invalid_argument("MakeJitterExperiment: needs samples");
  JitterExperiment e{test, {}, BaseParams(seed, frame, samples), {}};
  switch (test) {
    case JitterTest::kSquare:
    case JitterTest::kMean:
      for (std::uint32_t i = 0; i < samples; ++i) e.records.push_back(OffsetRecord(i, 0, 0));
      e.probabilities = Uniform(16 * 16);
      break;
    case JitterTest::kPixelPairs:
    case JitterTest::kSamplePairs:
    case JitterTest::kBouncePairs:
      for (std::uint32_t i = 0; i < samples; ++i) {
        const bool pixels = test == JitterTest::kPixelPairs, sample_pairs = test == JitterTest::kSamplePairs;
        e.records.push_back(OffsetRecord(pixels ? 2 * i : i, 0, 0));
        e.records.push_back(OffsetRecord(pixels ? 2 * i + 1 : i, sample_pairs ? 1 : 0, pixels || sample_pairs ? 0 : 1));
      }
      e.probabilities = Uniform(4 * 4 * 4 * 4);
      break;
    case JitterTest::kKernel: {
      // Points on a stratified grid of the unit cell, so each axis's landing chances average exactly to the
      // box-box convolution: 1/4, 1/2, 1/4 for the cells -1, 0, 1.
      const std::uint32_t side = std::max(1u, std::uint32_t(std::sqrt(double(samples))));
      for (std::uint32_t i = 0; i < side * side; ++i) {
        const glm::vec3 x(float((i % side + 0.5) / side), float((i / side + 0.5) / side), 0.5f);
        e.records.push_back(JitterRecord(i, 0, 0, x, kZ, kX, kY, x - kZ));
      }
      const double axis[] = {0.25, 0.5, 0.25};
      for (const double px : axis) {
        for (const double py : axis) e.probabilities.push_back(px * py);
      }
      e.probabilities.push_back(0.0);
      break;
    }
    case JitterTest::kLevelChange: {
      // Grazing incidence: the tangent runs along the ray, so u1 moves the path length by up to 2^l. Distances
      // stratified over [62, 130) straddle the level boundaries at 64 and 128.
      e.params.lod_enabled = 1u;
      e.params.footprint_scale = kLevelFootprint;
      e.probabilities.assign(4, 0.0);
      for (std::uint32_t i = 0; i < samples; ++i) {
        const double z = kLevelNearest + (kLevelFarthest - kLevelNearest) * (i + 0.5) / samples;
        e.records.push_back(JitterRecord(i, 0, 0, glm::vec3(0.0f, 0.0f, float(z)), kY, kZ, kX, glm::vec3(0.0f)));
        const std::vector<double> p =
            LevelChangeProbabilities(double(e.records.back().position.z), LevelBefore(e.records.back(), e.params));
        for (std::size_t c = 0; c < p.size(); ++c) e.probabilities[c] += p[c] / samples;
      }
      break;
    }
  }
  if (test != JitterTest::kLevelChange) {
    e.params.cell_size = test == JitterTest::kKernel ? 1.0f : 1.0f / 64.0f;
    e.params.inverse_cell_size = test == JitterTest::kKernel ? 1.0f : 64.0f;
    e.params.jitter_scale = test == JitterTest::kKernel ? 1.0f : 64.0f;
  }
  e.params.record_count = std::uint32_t(e.records.size());
  return e;
}

std::vector<std::uint64_t> CountJitterCells(const JitterExperiment& e, std::span<const KeyResult> keys) {
  if (keys.size() != e.records.size()) throw std::invalid_argument("CountJitterCells: one key per record");
  std::vector<std::uint64_t> counts(e.probabilities.size(), 0);
  const std::size_t outside = counts.size() - 1;
  auto keyed = [](const KeyResult& k) { return k.status == shared::kKeyed; };
  switch (e.test) {
    case JitterTest::kSquare:
    case JitterTest::kMean:
      for (const KeyResult& k : keys) {
        const int x = OffsetBin(k.words.cell_x, 16), y = OffsetBin(k.words.cell_y, 16);
        ++counts[keyed(k) && x >= 0 && y >= 0 ? std::size_t(x * 16 + y) : outside];
      }
      break;
    case JitterTest::kPixelPairs:
    case JitterTest::kSamplePairs:
    case JitterTest::kBouncePairs:
      for (std::size_t i = 0; i + 1 < keys.size(); i += 2) {
        const int bins[] = {OffsetBin(keys[i].words.cell_x, 4), OffsetBin(keys[i].words.cell_y, 4),
                            OffsetBin(keys[i + 1].words.cell_x, 4), OffsetBin(keys[i + 1].words.cell_y, 4)};
        bool inside = keyed(keys[i]) && keyed(keys[i + 1]);
        std::size_t cell = 0;
        for (const int b : bins) {
          inside = inside && b >= 0;
          cell = cell * 4 + std::size_t(std::max(b, 0));
        }
        ++counts[inside ? cell : outside];
      }
      break;
    case JitterTest::kKernel:
      for (const KeyResult& k : keys) {
        const int dx = int(k.words.cell_x), dy = int(k.words.cell_y);
        const bool inside = keyed(k) && std::abs(dx) <= 1 && std::abs(dy) <= 1 && k.words.cell_z == 0u;
        ++counts[inside ? std::size_t((dx + 1) * 3 + dy + 1) : outside];
      }
      break;
    case JitterTest::kLevelChange:
      for (std::size_t i = 0; i < keys.size(); ++i) {
        const int change = keys[i].level - LevelBefore(e.records[i], e.params);
        ++counts[keyed(keys[i]) && std::abs(change) <= 1 ? std::size_t(change + 1) : outside];
      }
      break;
  }
  return counts;
}

JitterVerdict RunJitterTest(const KeyPassFunction& pass, const JitterExperiment& e) {
  const std::vector<KeyResult> keys = pass(e.records, e.params);
  const bool pairs =
      e.test == JitterTest::kPixelPairs || e.test == JitterTest::kSamplePairs || e.test == JitterTest::kBouncePairs;
  JitterVerdict verdict{e.test, pairs ? keys.size() / 2 : keys.size(), {}};
  if (e.test != JitterTest::kMean) {
    verdict.chi_square = ChiSquareTest(CountJitterCells(e, keys), e.probabilities);
    return verdict;
  }
  // The offset read to 7 bits is (k + 1/2) / 64 for k uniform in [-64, 64): mean 0, variance (128^2 - 1) / 12 /
  // 64^2. A key outside the bins rejects outright.
  const double variance = (double(kOffsetCells) * kOffsetCells - 1.0) / 12.0 / (64.0 * 64.0);
  double sum[2] = {0.0, 0.0};
  for (const KeyResult& k : keys) {
    const std::uint32_t words[2] = {k.words.cell_x, k.words.cell_y};
    for (int axis = 0; axis < 2; ++axis) {
      if (k.status != shared::kKeyed || OffsetBin(words[axis], 16) < 0) {
        verdict.chi_square = {INFINITY, 2, 0.0};
        return verdict;
      }
      sum[axis] += (int(words[axis]) + 0.5) / 64.0;
    }
  }
  const double n = double(keys.size());
  for (const double s : sum) verdict.chi_square.statistic += (s / n) * (s / n) / (variance / n);
  verdict.chi_square.dof = 2;
  verdict.chi_square.p_value =
      boost::math::cdf(boost::math::complement(boost::math::chi_squared(2), verdict.chi_square.statistic));
  return verdict;
}

}  // namespace hpsf
