// Validation of a JSON document against a JSON Schema (draft 7, with valijson): the gate file's schema
// (verifier/gate/gate_schema.json) as the loader applies it, and any schema a test checks a file against (a CI
// configuration against its service's published schema, through tools/schema_check).
#ifndef HPSF_VERIFIER_GATE_JSON_SCHEMA_H
#define HPSF_VERIFIER_GATE_JSON_SCHEMA_H

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hpsf {

// Every violation, each "POINTER: what" (POINTER a JSON pointer into the document, "" for the whole of it). Empty
// when the document conforms. A schema valijson cannot read throws InputError.
std::vector<std::string> SchemaViolations(const nlohmann::json& schema, const nlohmann::json& document);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_JSON_SCHEMA_H
