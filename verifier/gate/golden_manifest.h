// golden/manifest.json: the golden cases. Each case is an `hpsf render SCENE` or `hpsf replay RECORDS` command
// line (so a person can rerun any case by hand), the backends that must reproduce it, its golden EXR, and how
// the new image is compared with the golden:
//   "exact": `hpsf diff`'s rule with the case's metric and thresholds (default: max, warn 0, fail 0, bit for
//            bit up to the sign of zero);
//   "statistical": the tile and image-mean Welch t-tests of `hpsf diff --statistical` at the case's alpha, on
//            images rendered with --variance; it survives a change of random numbers, not a bias.
// The golden is rendered by the first backend listed; paths are relative to the manifest's folder, where the
// renders run.
#ifndef HPSF_VERIFIER_GATE_GOLDEN_MANIFEST_H
#define HPSF_VERIFIER_GATE_GOLDEN_MANIFEST_H

#include <string>
#include <vector>

#include "verifier/gate/diff_thresholds.h"

namespace hpsf {

enum class GoldenComparison { kExact, kStatistical };

struct GoldenCase {
  std::string name;                   // unique, e.g. "cornell/fixed64"
  std::string scene;                  // a built-in scene or scene file, for `hpsf render`; or
  std::string records;                // a .hpsfv file, for `hpsf replay`, as written (the render runs in the
                                      // manifest's folder, so the image's metadata names it the same anywhere)
  std::vector<std::string> args;      // the rest of the command line: size, spp, seed, filter options
  std::vector<std::string> backends;  // reference, emulated, vulkan
  std::string golden;                 // the golden EXR (resolved against the manifest folder)
  GoldenComparison comparison = GoldenComparison::kExact;
  DiffThresholds thresholds{DiffMetric::kMaxAbs, 0.0, 0.0};
  double alpha = 0.01;  // statistical: the family's significance level
  // The command line that renders this case with `backend` into `output`, without the program name.
  std::vector<std::string> Command(const std::string& backend, const std::string& output) const;
};

struct GoldenManifest {
  std::string path;    // the manifest file
  std::string folder;  // its folder
  std::vector<GoldenCase> cases;
};

// Throws InputError naming the file and the case (index and name) and field at fault.
GoldenManifest ReadGoldenManifest(const std::string& path);

std::string ToString(GoldenComparison comparison);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_GOLDEN_MANIFEST_H
