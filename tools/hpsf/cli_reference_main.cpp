// cli_reference [OUT.md]: the command line's reference page (tools/hpsf/cli_reference.h), to OUT.md or stdout.
#include <fstream>
#include <iostream>

#include "tools/hpsf/cli_reference.h"
#include "tools/hpsf/command_context.h"
#include "tools/hpsf/commands.h"

int main(int argc, char** argv) {
  CLI::App app(hpsf::kHpsfDescription, "hpsf");
  hpsf::CommandContext context;
  hpsf::AddCommands(app, context);
  const std::string page = hpsf::CliReferenceMarkdown(app);
  if (argc < 2) {
    std::cout << page;
    return 0;
  }
  std::ofstream file(argv[1], std::ios::binary);
  file << page;
  return file.good() ? 0 : 1;
}
