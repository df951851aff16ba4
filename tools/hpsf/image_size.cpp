#include "tools/hpsf/image_size.h"

#include <regex>

#include "core/error.h"

namespace hpsf {

void ParseSize(const std::string& text, TraceOptions& trace) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((\d{1,5})x(\d{1,5}))"))) {
    throw ConfigError("--size", "expected WIDTHxHEIGHT, as in 256x256; got '" + text + "'");
  }
  trace.width = std::stoul(m[1]);
  trace.height = std::stoul(m[2]);
}

}  // namespace hpsf
