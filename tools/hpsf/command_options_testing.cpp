// The option-layer tests' shared parts: see command_options_testing.h.
#include "tools/hpsf/command_options_testing.h"

#include <unistd.h>

#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "tools/hpsf/commands.h"

namespace hpsf::command_options {

namespace fs = std::filesystem;

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

void CommandOptions::SetUp() {
  previous_ = fs::current_path();
  folder_ = fs::temp_directory_path() / ("hpsf_command_options_" + std::to_string(::getpid()));
  fs::remove_all(folder_);
  fs::create_directories(folder_);
  fs::current_path(folder_);
}

void CommandOptions::TearDown() {
  fs::current_path(previous_);
  fs::remove_all(folder_);
}

bool CommandOptions::FolderIsEmpty() const { return fs::is_empty(folder_); }

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

const std::vector<std::string>& EdgeValues() {
  // clang-format off
  static const std::vector<std::string> values = {
      "", "0", "1", "-1", "2", "7", "8", "32", "33", "64", "1023", "1024", "1025", "65536", "65537", "4294967295",
      "4294967296", "-2147483649", "18446744073709551616", "1e400", "-1e400", "nan", "inf", "-inf", "0.5",
      "1e-300", "-0", "0x0", "1x1", "64x48", "16384x16384", "16385x1", "4294967296x1", "x", "3x", "x3", "8x8x8",
      "cornell", "furnace", "cornell-tiny", "a.hpsfv", "a.exr", "a.json", "fixed64", "float32", "both", "fast",
      "faithful", "round-robin", "random:1", "pct:1:2", "pct:", "exhaustive", "none", "sign", "octahedral:0",
      "octahedral:24", "on", "off", "D2", "D3", "D8", "D8-unwrapped", "D9", "D13", "D1", "reference", "emulated",
      "vulkan", "reference,emulated", "emulated,,vulkan", ",", "always", "never", "auto", "mse", "psnr", "ssim",
      "max", "percentile", "fraction", "--", "-", "-126", "126", "127", "-127", "--help", "integrate", "adaptive",
      "strict", "2/3", "spp=1,2; method=pt,radius", "animation", "temporal", "linear", "bucket", "bucket-window",
      "any", "core", "shader", "occupied-list", "fingerprint", "full", "packed-decimal", "levels", "search",
      "levels,search", "table", "hashcache", "sort-reduce", "atomics", "reduce-off-by-one"};
  // clang-format on
  return values;
}

const std::vector<std::string>& CompoundValues() {
  static const std::vector<std::string> values = [] {
    // clang-format off
    const std::vector<std::string> numbers = {"0", "1", "-1", "65535", "65536", "2147483647", "2147483648",
                                              "4294967296", "18446744073709551616", "99999999999999999999", "1e400",
                                              "nan", "0.5", ""};
    // clang-format on
    std::vector<std::string> v;
    for (const std::string& n : numbers) {
      for (const std::string& s :
           {n + "x1", "1x" + n, n + "x" + n, "octahedral:" + n, "random:" + n, "pct:" + n + ":2", "pct:1:" + n,
            "ema:" + n, "ema:0.5:" + n, "stale:" + n, "bucket:" + n, "bucket-window:" + n, "linear:" + n}) {
        v.push_back(s);
      }
    }
    return v;
  }();
  return values;
}

std::vector<std::string> RequiredArguments(const std::vector<std::string>& path) {
  static const std::map<std::string, std::vector<std::string>> required = {{"render", {"cornell", "-o", "o.exr"}},
                                                                           {"replay", {"r.hpsfv", "-o", "o.exr"}},
                                                                           {"crosscheck", {"cornell"}},
                                                                           {"stats", {"furnace"}},
                                                                           {"diff", {"a.exr", "b.exr"}},
                                                                           {"judge", {"c.hpsfc"}},
                                                                           {"reference", {"cornell"}},
                                                                           {"sweep", {"cornell", "--grid", "spp=1"}}};
  const auto given = required.find(path.back());
  return given == required.end() ? std::vector<std::string>{} : given->second;
}

const std::vector<std::vector<std::string>>& CommandPaths() {
  static const std::vector<std::vector<std::string>> paths = {
      {"device"},          {"render"}, {"replay"}, {"crosscheck"}, {"stats"}, {"diff"}, {"golden", "check"},
      {"golden", "bless"}, {"fuzz"},   {"check"},  {"reference"},  {"sweep"}, {"judge"}};
  return paths;
}

}  // namespace hpsf::command_options
