// fuzz_declaration: table declarations (verifier/gate/table_declaration.h) through ApplyTableDeclarationText. Every
// input is a declaration whose config validates or an hpsf::InputError that names the file; a bug is a crash, a
// hang, a sanitizer report, any other exception, an accepted config that does not validate, or an error that does not
// name the file.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "verifier/gate/table_declaration.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hpsf;
  if (size > (1 << 14)) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  FilterConfig config;
  try {
    ApplyTableDeclarationText(text, "fuzz.json", config);
  } catch (const InputError& e) {
    if (std::string(e.what()).rfind("fuzz.json: ", 0) != 0) {
      std::fprintf(stderr, "fuzz_declaration: an error that does not name the file: %s\n", e.what());
      std::abort();
    }
    return 0;
  }
  config.Validate();  // throws, and so fails the target, if a declaration was accepted that does not validate
  return 0;
}
