#include "tools/calibration/statistical_calibration.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "reference/reference_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "verifier/metrics/pixel_variance.h"
#include "verifier/metrics/statistical_compare.h"

namespace hpsf {
namespace {

struct Render {
  NoisyImage filtered, unfiltered;
};

// One seed's render at one spp, filtered by the reference and plain, with their variances.
Render RenderOnce(const Scene& scene, const std::string& name, std::uint32_t size, std::uint32_t spp,
                  std::uint32_t seed) {
  TraceOptions trace;
  trace.width = trace.height = size;
  trace.samples_per_pixel = spp;
  trace.seed = seed;
  const RecordBatch batch = TraceRecords(scene, trace).batch;
  FilterConfig config;
  config.seed = seed;
  const FilterResult result = ReferenceFilter(batch, config);
  const std::string source = name + " seed " + std::to_string(seed) + " " + std::to_string(spp) + " spp";
  return {
      MakeNoisyImage(source, result.image, EstimatePixelVariance(batch, result.placement, result.cells.size()), spp),
      MakeNoisyImage(source, UnfilteredImage(batch), EstimatePixelVariance(batch, {}, 0), spp)};
}

// A render whose radiance is 1 + bias times the other's: its means by that factor, its variances by its square.
NoisyImage Scaled(NoisyImage image, double bias) {
  const float f = float(1.0 + bias);
  for (glm::vec3& v : image.mean.pixels) v *= f;
  for (glm::vec3& v : image.variance.pixels) v *= f * f;
  for (glm::vec3& v : image.tile_variance.pixels) v *= f * f;
  image.mean_variance *= double(f) * double(f);
  return image;
}

}  // namespace

std::vector<CalibrationRow> RunCalibration(const CalibrationPlan& plan, bool progress) {
  std::set<std::uint32_t> spps(plan.spps.begin(), plan.spps.end());
  if (plan.reference_spp) spps.insert(plan.reference_spp);
  using Key = std::tuple<std::size_t, bool, std::uint32_t, std::uint32_t>;  // scene, unfiltered, spp, other spp
  std::map<Key, CalibrationRow> rows;
  for (std::size_t s = 0; s < plan.scenes.size(); ++s) {
    const Scene scene = LoadScene(plan.scenes[s]);
    for (std::uint32_t pair = 0; pair < plan.pairs; ++pair) {
      const std::uint32_t seed_a = plan.first_seed + 2 * pair, seed_b = seed_a + 1;
      // The first image at the plan's spps, the second also at the reference's.
      std::map<std::uint32_t, Render> a, b;
      for (std::uint32_t spp : spps) {
        if (std::count(plan.spps.begin(), plan.spps.end(), spp)) {
          a.emplace(spp, RenderOnce(scene, plan.scenes[s], plan.size, spp, seed_a));
        }
        b.emplace(spp, RenderOnce(scene, plan.scenes[s], plan.size, spp, seed_b));
      }
      for (bool unfiltered : {false, true}) {
        for (std::uint32_t spp : plan.spps) {
          std::vector<std::uint32_t> others{spp};
          if (plan.reference_spp > spp) others.push_back(plan.reference_spp);
          for (std::uint32_t other : others) {
            CalibrationRow& row = rows[Key{s, unfiltered, spp, other}];
            if (row.pairs == 0) {
              row = {plan.scenes[s],
                     !unfiltered,
                     spp,
                     other,
                     0,
                     std::vector<std::uint32_t>(plan.alphas.size()),
                     std::vector<std::uint32_t>(plan.biases.size())};
            }
            const NoisyImage& x = unfiltered ? a.at(spp).unfiltered : a.at(spp).filtered;
            const NoisyImage& y = unfiltered ? b.at(other).unfiltered : b.at(other).filtered;
            ++row.pairs;
            for (std::size_t k = 0; k < plan.alphas.size(); ++k) {
              row.false_alarms[k] += !CompareStatistically(x, y, plan.alphas[k], 1).consistent;
            }
            for (std::size_t k = 0; k < plan.biases.size(); ++k) {
              row.detections[k] += !CompareStatistically(Scaled(x, plan.biases[k]), y, plan.alphas[0], 1).consistent;
            }
          }
        }
      }
      if (progress && (pair + 1) % 10 == 0) {
        std::fprintf(stderr, "%s: %u of %u pairs\n", plan.scenes[s].c_str(), pair + 1, plan.pairs);
      }
    }
  }
  std::vector<CalibrationRow> out;
  for (auto& [key, row] : rows) out.push_back(row);
  return out;
}

nlohmann::json ToJson(const CalibrationPlan& plan, const std::vector<CalibrationRow>& rows) {
  nlohmann::json j{{"size", plan.size},     {"pairs", plan.pairs},   {"first_seed", plan.first_seed},
                   {"alphas", plan.alphas}, {"biases", plan.biases}, {"rows", nlohmann::json::array()}};
  for (const CalibrationRow& r : rows) {
    j["rows"].push_back({{"scene", r.scene},
                         {"filtered", r.filtered},
                         {"spp", r.spp},
                         {"other_spp", r.other_spp},
                         {"pairs", r.pairs},
                         {"false_alarms", r.false_alarms},
                         {"detections", r.detections}});
  }
  return j;
}

std::string MarkdownTable(const CalibrationPlan& plan, const std::vector<CalibrationRow>& rows) {
  std::ostringstream out;
  out << "| scene | filter | spp | against | pairs |";
  for (double a : plan.alphas) out << " false alarms at " << a << " |";
  for (double b : plan.biases) out << " power vs " << b * 100 << "% bias |";
  out << "\n| --- | --- | --- | --- | --- |";
  for (std::size_t k = 0; k < plan.alphas.size() + plan.biases.size(); ++k) out << " --- |";
  out << "\n";
  char cell[64];
  for (const CalibrationRow& r : rows) {
    out << "| " << r.scene << " | " << (r.filtered ? "reference" : "none") << " | " << r.spp << " | " << r.other_spp
        << " spp | " << r.pairs << " |";
    for (std::uint32_t f : r.false_alarms) {
      std::snprintf(cell, sizeof cell, " %u (%.1f%%) |", f, 100.0 * f / r.pairs);
      out << cell;
    }
    for (std::uint32_t d : r.detections) {
      std::snprintf(cell, sizeof cell, " %.2f |", double(d) / r.pairs);
      out << cell;
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace hpsf
