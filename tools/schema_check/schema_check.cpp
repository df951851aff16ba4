// schema_check SCHEMA.json FILE: whether FILE (JSON, or YAML when it ends in .yml or .yaml) conforms to the JSON
// Schema SCHEMA.json. Exit 0 it does, 2 it does not (each violation printed with its place), 3 a file could not be
// read. CI configurations, which no runner here can run, are checked against their services' published schemas.
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/error.h"
#include "verifier/gate/json_schema.h"

namespace {

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// YAML 1.2's core schema: a plain scalar may be null, a boolean or a number; a quoted one is always a string.
nlohmann::json ToJson(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      return nullptr;
    case YAML::NodeType::Sequence: {
      nlohmann::json array = nlohmann::json::array();
      for (const YAML::Node& item : node) array.push_back(ToJson(item));
      return array;
    }
    case YAML::NodeType::Map: {
      nlohmann::json object = nlohmann::json::object();
      for (const auto& entry : node) object[entry.first.as<std::string>()] = ToJson(entry.second);
      return object;
    }
    case YAML::NodeType::Scalar:
      break;
  }
  const std::string text = node.Scalar();
  if (node.Tag() == "!") return text;  // quoted
  if (text == "null" || text == "~" || text.empty()) return nullptr;
  if (text == "true" || text == "false") return text == "true";
  const nlohmann::json number = nlohmann::json::parse(text, nullptr, false);
  return number.is_number() ? number : nlohmann::json(text);
}

nlohmann::json Read(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw hpsf::InputError(path + ": cannot open the file");
  std::stringstream text;
  text << file.rdbuf();
  try {
    if (EndsWith(path, ".yml") || EndsWith(path, ".yaml")) return ToJson(YAML::Load(text.str()));
    return nlohmann::json::parse(text.str());
  } catch (const std::exception& e) {
    throw hpsf::InputError(path + ": " + e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: schema_check SCHEMA.json FILE\n";
    return hpsf::kExitBadInput;
  }
  try {
    const std::vector<std::string> violations = hpsf::SchemaViolations(Read(argv[1]), Read(argv[2]));
    for (const std::string& v : violations) std::cout << argv[2] << ": " << v << "\n";
    if (!violations.empty()) return hpsf::kExitCheckFailed;
    std::cout << argv[2] << ": conforms to " << argv[1] << "\n";
    return hpsf::kExitOk;
  } catch (const hpsf::InputError& e) {
    std::cerr << "schema_check: " << e.what() << "\n";
    return hpsf::kExitBadInput;
  }
}
