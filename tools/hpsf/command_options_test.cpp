// The command line's option layer as main registers it (AddCommands), in options-only mode: every subcommand's
// options and resolvers, under fixed and generated argument lists. An argument list either parses, or fails
// with a CLI11 ParseError or an InputError (a ConfigError names its option); nothing else escapes, and no file
// is written. The libFuzzer target fuzz_cli covers the shared option groups with coverage guidance; these tests
// cover every command, diff, golden, fuzz and device included, in every build (the asan one too).
// command_option_sweep_test.cpp sweeps every option with every edge value.
#include <rapidcheck.h>

#include <cstdio>
#include <map>
#include <string>
#include <typeinfo>
#include <vector>

#include <gtest/gtest.h>

#include "tools/hpsf/command_options_testing.h"

namespace hpsf::command_options {
namespace {

// Each command with only what it requires: they parse and stop before their inputs, none of which exists here.
TEST_F(CommandOptions, EveryCommandParsesItsRequiredArgumentsAndStopsBeforeItsInputs) {
  const std::vector<std::vector<std::string>> lines = {
      {"device"},
      {"render", "cornell", "-o", "out.exr"},
      {"render", "missing-scene.json", "-o", "out.exr", "--backend", "emulated", "--mode", "faithful"},
      {"replay", "missing.hpsfv", "-o", "out.exr", "--backend", "vulkan"},
      {"crosscheck", "missing.hpsfv", "--backends", "reference,emulated,vulkan"},
      {"crosscheck", "cornell", "--size", "8x8", "--accum", "float32"},
      {"stats", "furnace", "--spp", "2"},
      {"diff", "a.exr", "b.exr", "--metric", "psnr", "--fail", "30"},
      {"golden", "check", "--manifest", "missing.json"},
      {"golden", "bless", "--manifest", "missing.json"},
      {"fuzz", "--backend", "vulkan", "--accumulate-spv", "missing.spv", "--accum", "fixed64", "--runs", "3"},
      {"fuzz", "--inject-defect", "D9", "--time", "0.5"},
      {"check", "--shard", "2/3", "--list"},
      {"check", "--merge", "missing-shard-1", "missing-shard-2", "--html", "gate.html"},
      {"reference", "cornell", "--spp", "64", "--pass-spp", "8", "-o", "ref.exr"},
      {"sweep", "missing-scene.json", "--grid", "spp=1,2; method=pt,radius; filter-width=2,4", "--seeds", "2"},
  };
  for (const auto& line : lines) {
    const Parse p = ParseOptionsOnly(line);
    EXPECT_EQ(p.outcome, Outcome::kParsed) << Join(line) << ": " << p.message;
  }
  EXPECT_TRUE(FolderIsEmpty());
}

// A bad value fails as bad input naming its option, whichever command and resolver meets it.
TEST_F(CommandOptions, BadValuesAreInputErrorsNamingTheirOption) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"render", "cornell", "-o", "o.exr", "--size", "0x4"}, "--size"},
      {{"render", "cornell", "-o", "o.exr", "--spp", "0"}, "--spp"},
      {{"render", "cornell", "-o", "o.exr", "--size", "16384x16384", "--spp", "16"}, "--spp"},
      {{"render", "cornell", "-o", "o.exr", "--max-depth", "-2"}, "--max-depth"},
      {{"render", "cornell", "-o", "o.exr", "--threads", "-1"}, "--threads"},
      {{"render", "cornell", "-o", "o.exr", "--backend", "gpu"}, "--backend"},
      {{"render", "cornell", "-o", "o.exr", "--inject-defect", "D7"}, "--inject-defect"},
      {{"replay", "a.hpsfv", "-o", "o.exr", "--mode", "slow"}, "--mode"},
      {{"replay", "a.hpsfv", "-o", "o.exr", "--capacity", "1000"}, "--capacity"},
      {{"crosscheck", "cornell", "--backends", "reference,gpu"}, "--backends"},
      {{"crosscheck", "cornell", "--size", "64"}, "--size"},
      {{"crosscheck", "cornell", "--fingerprint-bits", "40"}, "--fingerprint-bits"},
      {{"crosscheck", "cornell", "--probing", "cuckoo"}, "--probing"},
      {{"crosscheck", "cornell", "--probing", "bucket:12"}, "--probing"},
      {{"crosscheck", "cornell", "--probing", "bucket-window:8", "--probe-limit", "4"}, "--probing"},
      {{"render", "cornell", "-o", "o.exr", "--probing", "bucket-window:8192", "--capacity", "4096"}, "--probe-limit"},
      {{"crosscheck", "cornell", "--vk-staging", "sometimes"}, "--vk-staging"},
      {{"stats", "cornell", "--max-depth", "2000"}, "--max-depth"},
      {{"stats", "cornell", "--normal", "octahedral:99"}, "--normal"},
      {{"stats", "cornell", "--second-moments", "yes"}, "--second-moments"},
      {{"render", "cornell", "-o", "o.exr", "--second-moments", "on", "--accum", "packed-decimal"}, "--second-moments"},
      {{"crosscheck", "cornell", "--second-moments", "on", "--level-change", "seed"}, "--second-moments"},
      {{"diff", "a.exr", "b.exr", "--metric", "psnr"}, "--fail"},
      {{"diff", "a.exr", "b.exr", "--metric", "volume", "--fail", "1"}, "--metric"},
      {{"diff", "a.exr", "b.exr", "--warn", "1", "--fail", "0.5"}, "--warn"},
      {{"fuzz", "--backend", "reference"}, "--backend"},
      {{"fuzz", "--max-records", "1"}, "--max-records"},
      {{"fuzz", "--time", "0"}, "--time"},
      {{"fuzz", "--inject-defect", "D2", "--backend", "vulkan"}, "--inject-defect"},
      {{"fuzz", "--backend", "vulkan", "--accumulate-spv", "my.spv"}, "--accum"},
      {{"fuzz", "--accum", "float64"}, "--accum"},
      {{"fuzz", "--shaders-know", "levels,cuckoo"}, "--shaders-know"},
      {{"device", "--vk-staging", "sometimes"}, "--vk-staging"},
      {{"check", "--shard", "4/3"}, "--shard"},
      {{"check", "--merge", "a", "--shard", "1/2"}, "--merge"},
      {{"reference", "cornell", "--spp", "24", "--pass-spp", "16"}, "--spp"},
      {{"reference", "cornell", "--pass-spp", "0"}, "--pass-spp"},
      {{"sweep", "cornell", "--grid", "method=kd"}, "--grid"},
      {{"sweep", "cornell", "--grid", "jitter=x"}, "--grid"},
      {{"sweep", "cornell", "--grid", "method=hashcache; accum=packed-decimal"}, "--grid"},
      {{"sweep", "cornell", "--grid", "method=hashcache; cache-store=9"}, "--grid"},
      {{"sweep", "cornell", "--grid", "method=hashcache; cache-update=atomics; accum=float32"}, "--cache-update"},
      {{"sweep", "cornell", "--grid", "spp=1", "--seeds", "0"}, "--seeds"},
      {{"sweep", "cornell", "--grid", "spp=1", "--reference-spp", "20"}, "--spp"},
  };
  for (const auto& [line, option] : cases) {
    const Parse p = ParseOptionsOnly(line);
    EXPECT_EQ(p.outcome, Outcome::kInputError) << Join(line) << ": " << p.message;
    EXPECT_NE(p.message.find(option), std::string::npos) << Join(line) << ": '" << p.message << "' names no " << option;
  }
  EXPECT_TRUE(FolderIsEmpty());
}

// A generated line is the command's path, then items: mostly one of the command's own options (read from the
// App main builds, so a new option is generated the day it is added) with a value if it takes one, the value
// sitting on or beyond the edges the resolvers check; sometimes a stray value (a positional) or an arbitrary
// short string.
rc::Gen<std::vector<std::string>> GenItem(const std::vector<OptionName>& names) {
  const auto value = rc::gen::oneOf(rc::gen::elementOf(EdgeValues()), rc::gen::elementOf(CompoundValues()));
  const auto option = rc::gen::mapcat(rc::gen::elementOf(names), [value](const OptionName& o) {
    if (!o.takes_value) return rc::gen::just(std::vector<std::string>{o.name});
    return rc::gen::map(value, [o](const std::string& value) { return std::vector<std::string>{o.name, value}; });
  });
  const auto stray = rc::gen::map(rc::gen::elementOf(EdgeValues()),
                                  [](const std::string& value) { return std::vector<std::string>{value}; });
  const auto arbitrary = rc::gen::map(
      rc::gen::mapcat(
          rc::gen::inRange<std::size_t>(1, 6),
          [](std::size_t n) { return rc::gen::container<std::string>(n, rc::gen::inRange<char>(32, 127)); }),
      [](const std::string& word) { return std::vector<std::string>{word}; });
  return rc::gen::weightedOneOf<std::vector<std::string>>({{12, option}, {2, stray}, {1, arbitrary}});
}

rc::Gen<std::vector<std::string>> GenLine() {
  static std::map<std::vector<std::string>, std::vector<OptionName>> names;
  if (names.empty()) {
    for (const auto& path : CommandPaths()) names[path] = OptionNames(path);
  }
  return rc::gen::mapcat(rc::gen::elementOf(CommandPaths()), [](const std::vector<std::string>& path) {
    const auto items = rc::gen::mapcat(rc::gen::inRange<std::size_t>(0, 8), [path](std::size_t n) {
      return rc::gen::container<std::vector<std::vector<std::string>>>(n, GenItem(names.at(path)));
    });
    // What the command requires in three lines of four, so that most lines reach the resolvers.
    const auto with_required = rc::gen::weightedOneOf<bool>({{3, rc::gen::just(true)}, {1, rc::gen::just(false)}});
    return rc::gen::map(rc::gen::pair(with_required, items), [path](const auto& drawn) {
      std::vector<std::string> line = path;
      if (drawn.first) {
        for (const std::string& r : RequiredArguments(path)) line.push_back(r);
      }
      for (const auto& item : drawn.second) line.insert(line.end(), item.begin(), item.end());
      return line;
    });
  });
}

// The property, plus the check that its oracle is fed: generated lines both parse and fail, in each way.
TEST_F(CommandOptions, GeneratedLinesParseOrFailAsBadInputOnly) {
  std::map<Outcome, int> outcomes;
  const bool held = rc::check("a line parses or is a ParseError or InputError, and writes nothing", [&] {
    const std::vector<std::string> line = *GenLine();
    Parse p;
    try {
      p = ParseOptionsOnly(line);
    } catch (const std::exception& e) {
      RC_FAIL(Join(line) + ": escaped as " + typeid(e).name() + ": " + e.what());
    }
    ++outcomes[p.outcome];
    if (p.outcome != Outcome::kParsed) RC_ASSERT(!p.message.empty());
    RC_ASSERT(FolderIsEmpty());
  });
  EXPECT_TRUE(held);
  // With 500 lines (ctest's RC_PARAMS) each outcome is common; a generator that only ever made bad lines, or
  // options that all parse, would leave one at zero.
  EXPECT_GT(outcomes[Outcome::kParsed], 0);
  EXPECT_GT(outcomes[Outcome::kParseError], 0);
  EXPECT_GT(outcomes[Outcome::kInputError], 0);
  std::printf("parsed %d, parse errors %d, input errors %d\n", outcomes[Outcome::kParsed],
              outcomes[Outcome::kParseError], outcomes[Outcome::kInputError]);
}

}  // namespace
}  // namespace hpsf::command_options
