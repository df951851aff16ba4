// statistical_calibration: the false-alarm rate and power table of `hpsf diff --statistical` (docs/results.md,
// "Statistical comparison"). Usage: statistical_calibration [PAIRS [SIZE [SCENE...]]] > table.md, the table
// then its figures as JSON.
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "tools/calibration/statistical_calibration.h"

int main(int argc, char** argv) {
  hpsf::CalibrationPlan plan;
  if (argc > 1) plan.pairs = std::uint32_t(std::strtoul(argv[1], nullptr, 10));
  if (argc > 2) plan.size = std::uint32_t(std::strtoul(argv[2], nullptr, 10));
  if (argc > 3) plan.scenes.assign(argv + 3, argv + argc);
  if (plan.pairs == 0 || plan.size == 0) {
    std::fprintf(stderr, "usage: statistical_calibration [PAIRS [SIZE [SCENE...]]]\n");
    return 3;
  }
  const auto rows = hpsf::RunCalibration(plan, true);
  std::cout << hpsf::MarkdownTable(plan, rows) << "\n" << hpsf::ToJson(plan, rows).dump() << "\n";
  return 0;
}
