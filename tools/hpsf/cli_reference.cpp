#include "tools/hpsf/cli_reference.h"

#include <sstream>
#include <vector>

namespace hpsf {
namespace {

// A table cell: one line, pipes escaped.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

void WriteCommand(const CLI::App& command, const std::string& path, std::ostringstream& out) {
  out << "\n## `" << path << "`\n\n" << command.get_description() << "\n";
  const std::vector<const CLI::Option*> options =
      command.get_options([](const CLI::Option* o) { return o->get_name() != "--help" && o->get_name() != "-h"; });
  if (!options.empty()) {
    out << "\n| option | value | default | what it does |\n| --- | --- | --- | --- |\n";
    for (const CLI::Option* o : options) {
      std::string names = o->get_positional() ? o->get_name(true) : o->get_name(false, true);
      // A flag with a default reads "--x{false}": the braces are not part of its name.
      for (std::size_t open; (open = names.find('{')) != std::string::npos;) {
        names.erase(open, names.find('}', open) - open + 1);
      }
      const std::string value = o->get_type_name();
      const std::string fallback = o->get_required() ? "required" : o->get_default_str();
      out << "| `" << Cell(names) << "` | " << (value.empty() ? "" : "`" + Cell(value) + "`") << " | "
          << (fallback.empty() ? "" : "`" + Cell(fallback) + "`") << " | " << Cell(o->get_description()) << " |\n";
    }
  }
  for (const CLI::App* sub : command.get_subcommands([](const CLI::App*) { return true; })) {
    WriteCommand(*sub, path + " " + sub->get_name(), out);
  }
}

}  // namespace

std::string CliReferenceMarkdown(const CLI::App& app) {
  std::ostringstream out;
  out << "# Command-line reference\n\n"
      << "Generated from the command line's own definitions by `cli_reference`: `cmake --build --preset default\n"
         "--target cli-reference` rewrites this page, and the test `Docs.CliReferenceMatchesTheCommandLine` fails\n"
         "when it differs. Exit codes: [exit-codes.md](exit-codes.md).\n\n"
      << app.get_description() << "\n";
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    WriteCommand(*sub, app.get_name() + " " + sub->get_name(), out);
  }
  return out.str();
}

}  // namespace hpsf
