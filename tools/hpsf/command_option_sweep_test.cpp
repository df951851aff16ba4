// Every option of every command the command line registers, swept with every edge and compound value
// (command_options_testing.h): about 25,000 lines, labelled slow because ASan makes it the longest test of its
// run (100 s against 7 s); fuzz_cli covers the option groups under the sanitizers.
#include <cstdio>
#include <exception>
#include <string>
#include <typeinfo>
#include <vector>

#include <gtest/gtest.h>

#include "tools/hpsf/command_options_testing.h"

namespace hpsf::command_options {
namespace {

// Every option of every command with every edge and compound value, one at a time after what the command
// requires: each line parses or fails as bad input, and each option accepts some value (so its resolver runs).
TEST_F(CommandOptions, EveryOptionWithEveryEdgeValueParsesOrFailsAsBadInput) {
  std::vector<std::string> values = EdgeValues();
  for (const std::string& v : CompoundValues()) values.push_back(v);
  std::size_t lines = 0;
  for (const auto& path : CommandPaths()) {
    for (const OptionName& option : OptionNames(path)) {
      if (!option.takes_value || option.name.size() < 3) continue;  // flags; -o is --output
      std::size_t parsed = 0;
      for (const std::string& value : values) {
        std::vector<std::string> line = path;
        std::vector<std::string> required = RequiredArguments(path);
        if (option.name == "--output" && required.size() >= 2 && required[required.size() - 2] == "-o") {
          required.resize(required.size() - 2);  // the option swept is the required -o
        }
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

}  // namespace
}  // namespace hpsf::command_options
