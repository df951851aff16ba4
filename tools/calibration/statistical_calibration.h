// The false-alarm rate and the power of `hpsf diff --statistical`, measured rather than assumed: pairs of renders
// of one scene that differ only in their seed must be judged consistent with noise in all but alpha of the
// pairs, and one scaled by 1 + bias must be caught. Used by `statistical_calibration` (docs/results.md's table) and by
// the verdicts test that fails when the rates drift; every render is a fixed seed, so each count is one outcome.
#ifndef HPSF_TOOLS_CALIBRATION_STATISTICAL_CALIBRATION_H
#define HPSF_TOOLS_CALIBRATION_STATISTICAL_CALIBRATION_H

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hpsf {

struct CalibrationPlan {
  std::vector<std::string> scenes{"cornell", "furnace"};
  std::vector<std::uint32_t> spps{2, 4, 8, 16, 64};
  // Also each spp against a precise render of this many spp (the golden use: unequal spp); 0: none.
  std::uint32_t reference_spp = 256;
  std::uint32_t size = 64;  // square images
  std::uint32_t pairs = 200;
  std::uint32_t first_seed = 1;  // pair i renders seeds first_seed + 2i and + 2i + 1
  std::vector<double> alphas{0.01, 0.1};
  std::vector<double> biases{0.01, 0.05};  // power, at alphas[0]: the second image scaled by 1 + bias
};

struct CalibrationRow {
  std::string scene;
  bool filtered = true;
  std::uint32_t spp = 0;
  std::uint32_t other_spp = 0;  // the second image's: spp, or the plan's reference_spp
  std::uint32_t pairs = 0;
  std::vector<std::uint32_t> false_alarms;  // per alpha
  std::vector<std::uint32_t> detections;    // per bias
};

// The rows in the order scene, filtered then unfiltered, spp, equal then unequal; progress to stderr if asked.
std::vector<CalibrationRow> RunCalibration(const CalibrationPlan& plan, bool progress = false);

nlohmann::json ToJson(const CalibrationPlan& plan, const std::vector<CalibrationRow>& rows);
std::string MarkdownTable(const CalibrationPlan& plan, const std::vector<CalibrationRow>& rows);

}  // namespace hpsf

#endif  // HPSF_TOOLS_CALIBRATION_STATISTICAL_CALIBRATION_H
