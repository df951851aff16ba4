#include "verifier/gate/json_text.h"

#include "core/error.h"

namespace hpsf {

nlohmann::json ParseJsonText(const std::string& text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(source + ": not valid JSON at byte " + std::to_string(e.byte));
  } catch (const nlohmann::json::exception& e) {  // out_of_range.406: a number beyond double's range, e.g. 1e400
    throw InputError(source + ": not valid JSON: " + e.what());
  }
}

}  // namespace hpsf
