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

// A sequence's "gate-backends" names the family's backends it runs on (a pass not built on every backend): the other
// backends skip it, it is no option of the command, and a name that is not the family's is refused by the loader.
TEST(GateFile, ASequenceRunsOnTheBackendsItNames) {
  const std::string family = R"({"hpsf_gate": 1, "crosscheck": {"scenes": ["cornell"], "backends": {"e": {"backend": )"
                             R"("emulated"}, "v": {"backend": "vulkan"}}, "sequences": {"one-frame": {}, "t": )"
                             R"({"frames": 2, "transport": "on", "gate-backends": "e"}}}})";
  EXPECT_EQ(SchemaViolations(Schema(), json::parse(family)), std::vector<std::string>{});
  const Gate gate = ExpandGate(family, "gate.json", "");
  std::vector<std::string> ids;
  for (const GateCase& c : gate.cases) {
    ids.push_back(c.id);
    for (const std::string& a : c.arguments) EXPECT_EQ(a.find("gate-backends"), std::string::npos) << c.id;
  }
  EXPECT_EQ(ids, (std::vector<std::string>{"crosscheck/cornell/default/e/one-frame/seed1",
                                           "crosscheck/cornell/default/e/t/seed1",
                                           "crosscheck/cornell/default/v/one-frame/seed1"}));
  std::string unknown = family;
  unknown.replace(unknown.find(R"("gate-backends": "e")"), 20, R"("gate-backends": "x")");
  try {
    ExpandGate(unknown, "gate.json", "");
    ADD_FAILURE() << "the loader accepts an unknown backend name";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/crosscheck/sequences/t/gate-backends"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'x' names none of this family's backends"), std::string::npos) << e.what();
  }
}

// A sequence's "gate-configs" names the config sets it runs with (a pass some configs refuse, as second moments
// refuse packed-decimal sums): the other configs skip it, and an unknown name is refused with its place.
TEST(GateFile, ASequenceRunsWithTheConfigsItNames) {
  const std::string family = R"({"hpsf_gate": 1, "crosscheck": {"scenes": ["cornell"], "configs": {"a": {}, "p": )"
                             R"({"accum": "packed-decimal"}}, "backends": {"e": {"backend": "emulated"}}, )"
                             R"("sequences": {"one-frame": {}, "m": {"second-moments": "on", "gate-configs": "a"}}}})";
  EXPECT_EQ(SchemaViolations(Schema(), json::parse(family)), std::vector<std::string>{});
  const Gate gate = ExpandGate(family, "gate.json", "");
  std::vector<std::string> ids;
  for (const GateCase& c : gate.cases) {
    ids.push_back(c.id);
    for (const std::string& a : c.arguments) EXPECT_EQ(a.find("gate-configs"), std::string::npos) << c.id;
  }
  EXPECT_EQ(ids, (std::vector<std::string>{"crosscheck/cornell/a/e/m/seed1", "crosscheck/cornell/a/e/one-frame/seed1",
                                           "crosscheck/cornell/p/e/one-frame/seed1"}));
  std::string unknown = family;
  unknown.replace(unknown.find(R"("gate-configs": "a")"), 19, R"("gate-configs": "x")");
  try {
    ExpandGate(unknown, "gate.json", "");
    ADD_FAILURE() << "the loader accepts an unknown config name";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/crosscheck/sequences/m/gate-configs"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'x' names none of this family's configs"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hpsf
