// The gate file's JSON Schema (verifier/gate/gate_schema.json) and the loader say the same: every gate the project
// ships conforms, each bad gate below is refused by both, and the schema's backends are the registry's.
#include "verifier/gate/gate_schema.h"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/backend_registry.h"
#include "core/error.h"
#include "verifier/gate/gate_file.h"
#include "verifier/gate/json_schema.h"

namespace hpsf {
namespace {

using nlohmann::json;

json Schema() { return json::parse(kGateSchemaJson); }

TEST(GateSchema, ItsBackendsAreTheRegistrysHashedBackends) {
  std::vector<std::string> in_schema;
  const json schema = Schema();
  const json& names =
      schema["definitions"]["backendSets"]["patternProperties"]["^[^/]+$"]["allOf"][1]["properties"]["backend"]["enum"];
  for (const json& name : names) in_schema.push_back(name.get<std::string>());
  std::vector<std::string> registered;
  for (const BackendInfo& b : RegisteredBackends()) {
    if (b.hashed) registered.push_back(b.name);
  }
  std::sort(in_schema.begin(), in_schema.end());
  std::sort(registered.begin(), registered.end());
  EXPECT_EQ(in_schema, registered);
}

TEST(GateSchema, TheDefaultGateConforms) {
  // DefaultGate() applies the schema itself; a violation would throw.
  EXPECT_FALSE(DefaultGate().cases.empty());
}

TEST(GateSchema, EveryBadGateIsRefusedByTheSchemaAndByTheLoader) {
  const char* const scenes = R"("scenes": ["cornell"])";
  const std::vector<std::string> bad = {
      R"({"hpsf_gate": 2, "statistics": {)" + std::string(scenes) + "}}",
      R"({"hpsf_gate": 1, "name": "nothing"})",
      R"({"hpsf_gate": 1, "colours": 3, "statistics": {)" + std::string(scenes) + "}}",
      R"({"hpsf_gate": 1, "statistics": {"scenes": []}})",
      R"({"hpsf_gate": 1, "statistics": {)" + std::string(scenes) + R"(, "size": "12by12"}})",
      R"({"hpsf_gate": 1, "statistics": {)" + std::string(scenes) + R"(, "seeds": [-1]}})",
      R"({"hpsf_gate": 1, "statistics": {)" + std::string(scenes) + R"(, "configs": {"a": {"capacity": [1]}}}})",
      R"({"hpsf_gate": 1, "statistics": {)" + std::string(scenes) + R"(, "configs": {"a/b": {}}}})",
      R"({"hpsf_gate": 1, "crosscheck": {)" + std::string(scenes) + R"(, "backends": {"x": {"mode": "fast"}}}})",
      R"({"hpsf_gate": 1, "crosscheck": {)" + std::string(scenes) +
          R"(, "backends": {"x": {"backend": "reference"}}}})",
      R"({"hpsf_gate": 1, "fuzz": {"time": 60, "backends": {"x": {"backend": "emulated"}}}})",
      R"({"hpsf_gate": 1, "fuzz": {"runs": 0, "backends": {"x": {"backend": "emulated"}}}})",
      R"({"hpsf_gate": 1, "golden": {"cases": ["cornell/fixed64"]}})",
  };
  for (const std::string& text : bad) {
    EXPECT_FALSE(SchemaViolations(Schema(), json::parse(text)).empty()) << "the schema accepts " << text;
    EXPECT_THROW(ExpandGate(text, "gate.json", ""), InputError) << "the loader accepts " << text;
  }
  const std::string good = R"({"hpsf_gate": 1, "name": "ok", "statistics": {)" + std::string(scenes) +
                           R"(, "size": "16x16", "spp": 1, "seeds": [1, 2], "configs": {"a": {"capacity": 4096}}}})";
  EXPECT_EQ(SchemaViolations(Schema(), json::parse(good)), std::vector<std::string>{});
  EXPECT_EQ(ExpandGate(good, "gate.json", "").cases.size(), 2u);
}

}  // namespace
}  // namespace hpsf
