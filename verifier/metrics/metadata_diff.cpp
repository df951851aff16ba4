#include "verifier/metrics/metadata_diff.h"

#include <set>

namespace hpsf {

std::string MetadataDifference::ToString() const {
  auto shown = [](const std::optional<std::string>& v) { return v ? "'" + *v + "'" : std::string("(absent)"); };
  return key + ": " + shown(a) + " vs " + shown(b);
}

std::vector<MetadataDifference> DiffMetadata(const std::map<std::string, std::string>& a,
                                             const std::map<std::string, std::string>& b) {
  std::set<std::string> keys;
  for (const auto& entry : a) keys.insert(entry.first);
  for (const auto& entry : b) keys.insert(entry.first);
  std::vector<MetadataDifference> differences;
  for (const std::string& key : keys) {
    const auto in_a = a.find(key), in_b = b.find(key);
    MetadataDifference d{key, std::nullopt, std::nullopt};
    if (in_a != a.end()) d.a = in_a->second;
    if (in_b != b.end()) d.b = in_b->second;
    if (d.a != d.b) differences.push_back(d);
  }
  return differences;
}

nlohmann::json ToJson(const std::vector<MetadataDifference>& differences) {
  nlohmann::json list = nlohmann::json::array();
  for (const MetadataDifference& d : differences) {
    list.push_back({{"key", d.key},
                    {"a", d.a ? nlohmann::json(*d.a) : nlohmann::json(nullptr)},
                    {"b", d.b ? nlohmann::json(*d.b) : nlohmann::json(nullptr)}});
  }
  return list;
}

}  // namespace hpsf
