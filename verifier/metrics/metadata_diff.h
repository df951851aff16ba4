// What differs between two images' hpsf: metadata (scene, config, seed, backend, version, F, ...): a diff that
// only says "the pixels moved" leaves the reader to find out that the seed or the backend changed.
#ifndef HPSF_VERIFIER_METRICS_METADATA_DIFF_H
#define HPSF_VERIFIER_METRICS_METADATA_DIFF_H

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hpsf {

struct MetadataDifference {
  std::string key;
  std::optional<std::string> a, b;  // nullopt: the image has no such entry
  std::string ToString() const;
};

// Every key present in either map whose values differ, in key order.
std::vector<MetadataDifference> DiffMetadata(const std::map<std::string, std::string>& a,
                                             const std::map<std::string, std::string>& b);

nlohmann::json ToJson(const std::vector<MetadataDifference>& differences);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_METADATA_DIFF_H
