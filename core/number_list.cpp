#include "core/number_list.h"

#include <charconv>

namespace hpsf {

std::optional<std::vector<double>> ParseNumberList(const std::string& text, std::size_t from) {
  std::vector<double> values;
  const char* at = text.data() + from;
  const char* last = text.data() + text.size();
  while (true) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(at, last, value);
    if (error != std::errc() || end == at) return std::nullopt;
    values.push_back(value);
    if (end == last) return values;
    if (*end != ':') return std::nullopt;
    at = end + 1;
  }
}

}  // namespace hpsf
