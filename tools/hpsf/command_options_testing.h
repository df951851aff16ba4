// What the option-layer tests share (command_options_test.cpp, command_option_sweep_test.cpp): a line parsed by
// the commands main registers (AddCommands) in options-only mode, a folder that must stay empty, and the values
// and command paths the lines are made of.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace hpsf::command_options {

enum class Outcome { kParsed, kParseError, kInputError };

struct Parse {
  Outcome outcome;
  std::string message;
};

// Parses "hpsf WORDS..." in options-only mode. Anything but a CLI11 ParseError or an InputError propagates: the
// test fails on it.
Parse ParseOptionsOnly(const std::vector<std::string>& words);

// The line quoted word by word, for failure messages.
std::string Join(const std::vector<std::string>& words);

// Each test runs in an empty folder of its own and checks that it stays empty: options-only means no output.
class CommandOptions : public testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  bool FolderIsEmpty() const;

 private:
  std::filesystem::path previous_, folder_;
};

struct OptionName {
  std::string name;
  bool takes_value;
};

// The options of the command at PATH (e.g. {"golden", "check"}), read from the App main builds, so a new option
// is swept and generated the day it is added.
std::vector<OptionName> OptionNames(const std::vector<std::string>& path);

// Values on or beyond the edges the resolvers check, one word each.
const std::vector<std::string>& EdgeValues();

// Numbers at the edges of each integer and float type, inside the shapes the resolvers split: WxH, NAME:N,
// pct:SEED:DEPTH.
const std::vector<std::string>& CompoundValues();

// What the command at PATH requires (its positionals and -o), so that a line reaches the resolvers.
std::vector<std::string> RequiredArguments(const std::vector<std::string>& path);

// Every command path main registers.
const std::vector<std::vector<std::string>>& CommandPaths();

}  // namespace hpsf::command_options
