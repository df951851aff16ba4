#include "verifier/gate/json_schema.h"

#include <exception>

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include "core/error.h"

namespace hpsf {
namespace {

// valijson's context is {"<root>", "[key]", "[0]", ...}: a JSON pointer is /key/0.
std::string Pointer(const std::vector<std::string>& context) {
  std::string pointer;
  for (const std::string& step : context) {
    if (step == "<root>") continue;
    const bool bracketed = step.size() >= 2 && step.front() == '[' && step.back() == ']';
    std::string name = bracketed ? step.substr(1, step.size() - 2) : step;
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
    pointer += "/" + name;
  }
  return pointer;
}

}  // namespace

std::vector<std::string> SchemaViolations(const nlohmann::json& schema, const nlohmann::json& document) {
  valijson::Schema parsed;
  try {
    valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
    valijson::adapters::NlohmannJsonAdapter adapter(schema);
    parser.populateSchema(adapter, parsed);
  } catch (const std::exception& e) {
    throw InputError(std::string("a JSON Schema valijson cannot read: ") + e.what());
  }
  valijson::Validator validator;
  valijson::ValidationResults results;
  const valijson::adapters::NlohmannJsonAdapter target(document);
  std::vector<std::string> violations;
  if (validator.validate(parsed, target, &results)) return violations;
  valijson::ValidationResults::Error error;
  while (results.popError(error)) violations.push_back(Pointer(error.context) + ": " + error.description);
  return violations;
}

}  // namespace hpsf
