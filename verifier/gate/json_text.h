// JSON that a user hands hpsf (gate files, golden manifests, table declarations), parsed once with the same errors:
// not JSON at all, or a number beyond double's range (nlohmann's out_of_range, not a parse_error), is an InputError
// naming `source`.
#ifndef HPSF_VERIFIER_GATE_JSON_TEXT_H
#define HPSF_VERIFIER_GATE_JSON_TEXT_H

#include <string>

#include <nlohmann/json.hpp>

namespace hpsf {

nlohmann::json ParseJsonText(const std::string& text, const std::string& source);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_JSON_TEXT_H
