// fuzz_cli: the command line's option layer, without running a command (hpsf's commands do their work in their
// CLI11 callbacks). The input is argv, one word per line, for an App whose subcommands render, replay,
// crosscheck and stats register the real option groups (AddFilterOptions, AddEmulatorOptions: --mode, --warp-size,
// --schedule, --vk-staging, --inject-defect ..., AddBounceOptions: --filtered-vertices, --continuation-depth,
// AddAdaptiveTraceOptions: --survival, --path-graph) and the
// trace options as the commands do, and whose callbacks run the real resolvers (ResolveFilterConfig,
// ResolveEmulatorOptions, ParseDefect, ParseSize, CheckVarianceSamples, TraceScatteredVertices,
// TraceOptions::Validate). Success, CLI::ParseError (help included) and hpsf::InputError are the outcomes; anything
// else (another exception, a crash, a sanitizer report) is a bug. Every command's own registration, diff, golden, fuzz
// and device included, is run in options-only mode by command_options_tests (tools/hpsf/command_options_test.cpp),
// which needs the whole tool; this target keeps the fuzz build free of Vulkan, Embree and OpenImageIO.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "emulated/defect_injection.h"
#include "tools/hpsf/bounce_options.h"
#include "tools/hpsf/emulator_options.h"
#include "tools/hpsf/filter_options.h"
#include "tools/hpsf/image_size.h"

namespace hpsf {
namespace {

constexpr std::size_t kMaxInputBytes = 4096;
constexpr std::size_t kMaxWords = 64;

struct CommandOptions {
  std::string input, output = "out.exr", size = "256x256", backend = "reference";
  bool json = false;
  TraceOptions trace;
  FilterOptions filter;
  EmulatorFlags emulator;
};

CLI::App* AddCommand(CLI::App& app, const char* name, CommandOptions& o, bool emulator, bool traced) {
  CLI::App* c = app.add_subcommand(name, name);
  c->add_option("input", o.input, "scene or records")->required();
  if (std::string_view(name) == "render" || std::string_view(name) == "replay")
    c->add_option("-o,--output", o.output, "EXR")->required();
  AddFilterOptions(*c, o.filter);
  if (emulator) AddEmulatorOptions(*c, o.emulator);
  c->add_option("--backend", o.backend, "backend");
  c->add_flag("--json", o.json, "JSON report");
  if (traced) {
    c->add_option("--size", o.size, "WIDTHxHEIGHT");
    c->add_option("--spp", o.trace.samples_per_pixel, "samples per pixel");
    c->add_option("--max-depth", o.trace.max_depth, "surface vertices per path");
    c->add_option("--filter-bounce", o.trace.filter_bounce, "filtered vertex");
    c->add_option("--threads", o.trace.threads, "tracing threads");
    AddBounceOptions(*c, o.trace);
    AddAdaptiveTraceOptions(*c, o.filter.config);
  }
  c->callback([&o, emulator, traced] {
    if (emulator) {
      ResolveEmulatorOptions(o.emulator);
      ParseDefect(o.emulator.defect);
    }
    const FilterConfig config = ResolveFilterConfig(o.filter);
    if (traced) {
      ParseSize(o.size, o.trace);
      CheckVarianceSamples(o.filter, o.trace.samples_per_pixel, "--spp");
      TraceScatteredVertices(config, o.trace);
      CheckAdaptiveTrace(config, o.trace);
      o.trace.Validate();
    }
  });
  return c;
}

std::vector<std::string> Words(std::string_view input) {
  std::vector<std::string> words = {"hpsf"};
  while (words.size() <= kMaxWords) {
    const std::size_t end = input.find('\n');
    words.emplace_back(input.substr(0, end));
    if (end == std::string_view::npos) break;
    input.remove_prefix(end + 1);
  }
  return words;
}

}  // namespace
}  // namespace hpsf

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hpsf;
  if (size > kMaxInputBytes) return 0;
  std::vector<std::string> words = Words(std::string_view(reinterpret_cast<const char*>(data), size));
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());

  CLI::App app("hpsf", "hpsf");
  app.require_subcommand(1);
  CommandOptions render, replay, crosscheck, stats;
  AddCommand(app, "render", render, true, true);
  AddCommand(app, "replay", replay, true, false);
  AddCommand(app, "crosscheck", crosscheck, true, true);
  AddCommand(app, "stats", stats, false, true);
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError&) {
  } catch (const InputError&) {
  }
  return 0;
}
