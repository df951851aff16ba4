// The command line's option layer as main registers it (AddCommands), in options-only mode: every subcommand's
// options and resolvers, under fixed and generated argument lists. An argument list either parses, or fails
// with a CLI11 ParseError or an InputError (a ConfigError names its option); nothing else escapes, and no file
// is written. The libFuzzer target fuzz_cli covers the shared option groups with coverage guidance; this test
// covers every command, diff, golden, fuzz and device included, in every build (the asan one too).
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <typeinfo>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include "core/error.h"
#include "tools/hpsf/commands.h"

namespace hpsf {
namespace {

namespace fs = std::filesystem;

enum class Outcome { kParsed, kParseError, kInputError };

struct Parse {
  Outcome outcome;
  std::string message;
};

// Anything but a ParseError or an InputError propagates: the test fails on it.
Parse ParseOptionsOnly(const std::vector<std::string>& words) {
  CLI::App app("hpsf", "hpsf");
  CommandContext context;
  context.options_only = true;
  AddCommands(app, context);
  std::vector<std::string> argv = {"hpsf"};
  argv.insert(argv.end(), words.begin(), words.end());
  std::vector<char*> pointers;
  for (std::string& word : argv) pointers.push_back(word.data());
  try {
    app.parse(int(pointers.size()), pointers.data());
  } catch (const CLI::ParseError& e) {
    return {Outcome::kParseError, e.what()};
  } catch (const InputError& e) {
    return {Outcome::kInputError, e.what()};
  }
  return {Outcome::kParsed, {}};
}

std::string Join(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& w : words) line += (line.empty() ? "'" : " '") + w + "'";
  return line;
}

// Each test runs in an empty folder of its own and checks that it stays empty: options-only means no output.
class CommandOptions : public testing::Test {
 protected:
  void SetUp() override {
    previous_ = fs::current_path();
    folder_ = fs::temp_directory_path() / ("hpsf_command_options_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    fs::current_path(folder_);
  }
  void TearDown() override {
    fs::current_path(previous_);
    fs::remove_all(folder_);
  }
  bool FolderIsEmpty() const { return fs::is_empty(folder_); }

 private:
  fs::path previous_, folder_;
};

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
      {{"crosscheck", "cornell", "--vk-staging", "sometimes"}, "--vk-staging"},
      {{"stats", "cornell", "--max-depth", "2000"}, "--max-depth"},
      {{"stats", "cornell", "--normal", "octahedral:99"}, "--normal"},
      {{"diff", "a.exr", "b.exr", "--metric", "psnr"}, "--fail"},
      {{"diff", "a.exr", "b.exr", "--metric", "volume", "--fail", "1"}, "--metric"},
      {{"diff", "a.exr", "b.exr", "--warn", "1", "--fail", "0.5"}, "--warn"},
      {{"fuzz", "--backend", "reference"}, "--backend"},
      {{"fuzz", "--max-records", "1"}, "--max-records"},
      {{"fuzz", "--time", "0"}, "--time"},
      {{"fuzz", "--inject-defect", "D2", "--backend", "vulkan"}, "--inject-defect"},
      {{"fuzz", "--backend", "vulkan", "--accumulate-spv", "my.spv"}, "--accum"},
      {{"fuzz", "--accum", "float64"}, "--accum"},
      {{"device", "--vk-staging", "sometimes"}, "--vk-staging"},
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
struct OptionName {
  std::string name;
  bool takes_value;
};

std::vector<OptionName> OptionNames(const std::vector<std::string>& path) {
  CLI::App app("hpsf", "hpsf");
  CommandContext context;
  AddCommands(app, context);
  const CLI::App* command = &app;
  for (const std::string& name : path) command = command->get_subcommand(name);
  std::vector<OptionName> names;
  for (const CLI::Option* option : command->get_options()) {
    if (option == command->get_help_ptr()) continue;  // a stray value says --help now and then
    const bool takes_value = option->get_type_size() != 0;
    for (const std::string& l : option->get_lnames()) names.push_back({"--" + l, takes_value});
    for (const std::string& s : option->get_snames()) names.push_back({"-" + s, takes_value});
  }
  return names;
}

const std::vector<std::string> kEdgeValues = {"",
                                              "0",
                                              "1",
                                              "-1",
                                              "2",
                                              "7",
                                              "8",
                                              "32",
                                              "33",
                                              "64",
                                              "1023",
                                              "1024",
                                              "1025",
                                              "65536",
                                              "65537",
                                              "4294967295",
                                              "4294967296",
                                              "-2147483649",
                                              "18446744073709551616",
                                              "1e400",
                                              "-1e400",
                                              "nan",
                                              "inf",
                                              "-inf",
                                              "0.5",
                                              "1e-300",
                                              "-0",
                                              "0x0",
                                              "1x1",
                                              "64x48",
                                              "16384x16384",
                                              "16385x1",
                                              "4294967296x1",
                                              "x",
                                              "3x",
                                              "x3",
                                              "8x8x8",
                                              "cornell",
                                              "furnace",
                                              "cornell-tiny",
                                              "a.hpsfv",
                                              "a.exr",
                                              "a.json",
                                              "fixed64",
                                              "float32",
                                              "both",
                                              "fast",
                                              "faithful",
                                              "round-robin",
                                              "random:1",
                                              "pct:1:2",
                                              "pct:",
                                              "exhaustive",
                                              "none",
                                              "sign",
                                              "octahedral:0",
                                              "octahedral:24",
                                              "on",
                                              "off",
                                              "D2",
                                              "D3",
                                              "D8",
                                              "D8-unwrapped",
                                              "D9",
                                              "D13",
                                              "D1",
                                              "reference",
                                              "emulated",
                                              "vulkan",
                                              "reference,emulated",
                                              "emulated,,vulkan",
                                              ",",
                                              "always",
                                              "never",
                                              "auto",
                                              "mse",
                                              "psnr",
                                              "ssim",
                                              "max",
                                              "percentile",
                                              "fraction",
                                              "--",
                                              "-",
                                              "-126",
                                              "126",
                                              "127",
                                              "-127",
                                              "--help"};

// Numbers at the edges of each integer and float type, inside the shapes the resolvers split: WxH, NAME:N,
// pct:SEED:DEPTH.
std::vector<std::string> CompoundValues() {
  const std::vector<std::string> numbers = {"0",
                                            "1",
                                            "-1",
                                            "65535",
                                            "65536",
                                            "2147483647",
                                            "2147483648",
                                            "4294967296",
                                            "18446744073709551616",
                                            "99999999999999999999",
                                            "1e400",
                                            "nan",
                                            "0.5",
                                            ""};
  std::vector<std::string> values;
  for (const std::string& n : numbers) {
    for (const std::string& v :
         {n + "x1", "1x" + n, n + "x" + n, "octahedral:" + n, "random:" + n, "pct:" + n + ":2", "pct:1:" + n}) {
      values.push_back(v);
    }
  }
  return values;
}

rc::Gen<std::vector<std::string>> GenItem(const std::vector<OptionName>& names) {
  static const std::vector<std::string> compound = CompoundValues();
  const auto value = rc::gen::oneOf(rc::gen::elementOf(kEdgeValues), rc::gen::elementOf(compound));
  const auto option = rc::gen::mapcat(rc::gen::elementOf(names), [value](const OptionName& o) {
    if (!o.takes_value) return rc::gen::just(std::vector<std::string>{o.name});
    return rc::gen::map(value, [o](const std::string& value) { return std::vector<std::string>{o.name, value}; });
  });
  const auto stray = rc::gen::map(rc::gen::elementOf(kEdgeValues),
                                  [](const std::string& value) { return std::vector<std::string>{value}; });
  const auto arbitrary = rc::gen::map(
      rc::gen::mapcat(
          rc::gen::inRange<std::size_t>(1, 6),
          [](std::size_t n) { return rc::gen::container<std::string>(n, rc::gen::inRange<char>(32, 127)); }),
      [](const std::string& word) { return std::vector<std::string>{word}; });
  return rc::gen::weightedOneOf<std::vector<std::string>>({{12, option}, {2, stray}, {1, arbitrary}});
}

std::vector<std::string> RequiredArguments(const std::vector<std::string>& path) {
  static const std::map<std::string, std::vector<std::string>> required = {{"render", {"cornell", "-o", "o.exr"}},
                                                                           {"replay", {"r.hpsfv", "-o", "o.exr"}},
                                                                           {"crosscheck", {"cornell"}},
                                                                           {"stats", {"furnace"}},
                                                                           {"diff", {"a.exr", "b.exr"}}};
  const auto given = required.find(path.back());
  return given == required.end() ? std::vector<std::string>{} : given->second;
}

const std::vector<std::vector<std::string>> kCommandPaths = {{"device"},          {"render"},          {"replay"},
                                                             {"crosscheck"},      {"stats"},           {"diff"},
                                                             {"golden", "check"}, {"golden", "bless"}, {"fuzz"}};

// Every option of every command with every edge and compound value, one at a time after what the command
// requires: each line parses or fails as bad input, and each option accepts some value (so its resolver runs).
TEST_F(CommandOptions, EveryOptionWithEveryEdgeValueParsesOrFailsAsBadInput) {
  std::vector<std::string> values = kEdgeValues;
  for (const std::string& v : CompoundValues()) values.push_back(v);
  std::size_t lines = 0;
  for (const auto& path : kCommandPaths) {
    for (const OptionName& option : OptionNames(path)) {
      if (!option.takes_value || option.name.size() < 3) continue;  // flags; -o is --output
      std::size_t parsed = 0;
      for (const std::string& value : values) {
        std::vector<std::string> line = path;
        std::vector<std::string> required = RequiredArguments(path);
        if (option.name == "--output") required.resize(required.size() - 2);  // the option swept is -o
        for (const std::string& r : required) line.push_back(r);
        line.push_back(option.name);
        line.push_back(value);
        ++lines;
        try {
          parsed += ParseOptionsOnly(line).outcome == Outcome::kParsed;
        } catch (const std::exception& e) {
          ADD_FAILURE() << Join(line) << ": escaped as " << typeid(e).name() << ": " << e.what();
        }
      }
      EXPECT_GT(parsed, 0u) << Join(path) << " " << option.name << " accepts none of the values";
    }
  }
  std::printf("%zu lines\n", lines);
  EXPECT_TRUE(FolderIsEmpty());
}

rc::Gen<std::vector<std::string>> GenLine() {
  static std::map<std::vector<std::string>, std::vector<OptionName>> names;
  if (names.empty()) {
    for (const auto& path : kCommandPaths) names[path] = OptionNames(path);
  }
  return rc::gen::mapcat(rc::gen::elementOf(kCommandPaths), [](const std::vector<std::string>& path) {
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
}  // namespace hpsf
