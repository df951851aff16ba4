// A fuzz failure's bundle reruns `hpsf crosscheck` with CrosscheckArguments: those arguments, parsed by the
// crosscheck's own filter options, must give back the case's configuration field for field (ToJson), or the bundle
// reruns another case and reports a pass. Over the fuzzer's drawn cases: every probing scheme, accumulation, temporal
// mode, eviction, levels, search, transport, second moments and interpolation it draws.
#include "tools/hpsf/repro_bundle.h"

#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "tools/hpsf/filter_options.h"
#include "verifier/fuzzing/adversarial_case.h"

namespace hpsf {
namespace {

FilterConfig Reparsed(const std::vector<std::string>& arguments) {
  CLI::App app;
  app.allow_extras();  // the backend, emulator and Vulkan options, which are not the filter's
  FilterOptions options;
  AddFilterOptions(app, options);
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());  // CLI11 parses a vector from its back
  app.parse(reversed);
  return ResolveFilterConfig(options);
}

TEST(ReproBundle, ItsArgumentsGiveBackTheCasesConfiguration) {
  int second_moments = 0, interpolating = 0;
  for (std::uint64_t run = 0; run < 600; ++run) {
    const AdversarialCase c = MakeAdversarialCase(5, run);
    const std::vector<std::string> arguments =
        CrosscheckArguments({"reference", "emulated"}, c.config, c.emulator, Defect::kNone, {});
    FilterConfig reparsed = Reparsed(arguments);
    reparsed.frame = c.config.frame;  // the record file holds the frames and their numbers
    reparsed.frames = c.config.frames;
    ASSERT_EQ(ToJson(reparsed).dump(), ToJson(c.config).dump()) << "run " << run;
    second_moments += c.config.second_moments;
    interpolating += c.config.interpolation.enabled();
  }
  EXPECT_GT(second_moments, 0);
  EXPECT_GT(interpolating, 0);
}

}  // namespace
}  // namespace hpsf
