#include "tools/hpsf/sweep_grid.h"

#include <algorithm>
#include <charconv>
#include <set>

#include "core/backend_registry.h"
#include "core/error.h"
#include "core/path_graph.h"
#include "core/survival.h"
#include "tracer/trace_options.h"

namespace hpsf {
namespace {

std::string Trimmed(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\n");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\n") - first + 1);
}

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = text.find(separator, start);
    parts.push_back(Trimmed(text.substr(start, end == std::string::npos ? std::string::npos : end - start)));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

// The whole of `value` as an integer in [low, high], or nothing.
std::optional<long> Integer(const std::string& value, long low, long high) {
  long n = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), n);
  if (error != std::errc() || end != value.data() + value.size() || n < low || n > high) return std::nullopt;
  return n;
}

constexpr long kMaxFrames = 4096;

void CheckValue(const std::string& axis, const std::string& value) {
  const auto refuse = [&](const std::string& why) { throw ConfigError("--grid", axis + "=" + value + ": " + why); };
  if (axis == "spp") {
    if (!Integer(value, 1, 0xFFFFFFFFl)) refuse("a positive sample count");
  } else if (axis == "frames") {
    if (!Integer(value, 1, kMaxFrames)) refuse("a frame count in [1, " + std::to_string(kMaxFrames) + "]");
  } else if (axis == "max-depth") {
    if (!Integer(value, -1, 1024)) refuse("-1 (unbounded) or a depth in [0, 1024]");
  } else if (axis == "filtered-vertices") {
    if (!Integer(value, 1, kMaxFilteredVertices)) {
      refuse("a count in [1, " + std::to_string(kMaxFilteredVertices) + "]");
    }
  } else if (axis == "continuation-depth") {
    if (!Integer(value, 1, 1024)) refuse("a depth in [1, 1024]");
  } else if (axis == "survival") {
    try {
      ParseSurvival(value);
    } catch (const ConfigError& e) {
      refuse(std::string("a --survival rule: ") + e.what());
    }
  } else if (axis == "path-graph") {
    try {
      ParsePathGraph(value);
    } catch (const ConfigError& e) {
      refuse(std::string("a --path-graph bound: ") + e.what());
    }
  } else if (axis == "cache-resolution") {
    if (!Integer(value, 2, 10)) refuse("L in [2, 10]: 2^L finest cells per axis");
  } else if (axis == "cache-store" || axis == "cache-length") {
    if (!Integer(value, 1, 8)) refuse("a vertex count in [1, 8]");
  } else if (axis == "cache-update") {
    if (value != "sort-reduce" && value != "atomics") refuse("expected sort-reduce or atomics");
  } else if (axis == "transport") {
    refuse("the transport is the method's: method=nhpsf or anhpsf filter with it, hpsf without");
  } else if (axis == "method") {
    if (value != "pt" && value != "hpsf" && value != "nhpsf" && value != "anhpsf" && value != "radius" &&
        value != "screen" && value != "hashcache") {
      refuse("expected pt, hpsf, nhpsf, anhpsf, radius, screen or hashcache");
    }
  } else if (axis == "backend") {
    const auto backends = RegisteredBackends();
    if (std::none_of(backends.begin(), backends.end(), [&](const BackendInfo& b) { return value == b.name; })) {
      refuse("expected one of " + BackendNames());
    }
  }
}

}  // namespace

std::vector<std::string> SweepConfig::FilterArguments() const {
  std::vector<std::string> words;
  for (const auto& [name, value] : filter) words.insert(words.end(), {"--" + name, value});
  return words;
}

bool SweepConfig::Hashed() const { return method == "hpsf" || Transports(); }

bool SweepConfig::Transports() const { return method == "nhpsf" || method == "anhpsf"; }

bool SweepConfig::UsesBackend() const { return Hashed() || method == "hashcache"; }

std::vector<GridAxis> ParseGrid(const std::string& text) {
  std::vector<GridAxis> axes;
  std::set<std::string> names;
  for (const std::string& part : Split(text, ';')) {
    if (part.empty()) continue;
    const std::size_t equals = part.find('=');
    if (equals == std::string::npos) throw ConfigError("--grid", "'" + part + "': expected NAME=V1,V2,...");
    GridAxis axis{Trimmed(part.substr(0, equals)), Split(part.substr(equals + 1), ',')};
    if (axis.name.empty() || axis.name[0] == '-') {
      throw ConfigError("--grid", "'" + part + "': an axis is an option's name without its dashes");
    }
    if (!names.insert(axis.name).second) throw ConfigError("--grid", "the axis " + axis.name + " is given twice");
    for (const std::string& value : axis.values) {
      if (value.empty()) throw ConfigError("--grid", axis.name + ": an empty value");
      CheckValue(axis.name, value);
    }
    axes.push_back(std::move(axis));
  }
  if (axes.empty()) throw ConfigError("--grid", "no axis: expected e.g. \"spp=1,4; method=pt,hpsf\"");
  return axes;
}

std::vector<SweepConfig> ExpandGrid(const std::vector<GridAxis>& axes) {
  std::vector<SweepConfig> configs;
  std::set<std::string> seen;
  std::vector<std::size_t> at(axes.size(), 0);
  for (;;) {
    SweepConfig c;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const std::string& value = axes[a].values[at[a]];
      if (axes[a].name == "spp") {
        c.spp = std::uint32_t(std::stoul(value));
      } else if (axes[a].name == "frames") {
        c.frames = std::uint32_t(std::stoul(value));
      } else if (axes[a].name == "max-depth") {
        c.max_depth = std::stoi(value);
      } else if (axes[a].name == "filtered-vertices") {
        c.filtered_vertices = std::uint32_t(std::stoul(value));
      } else if (axes[a].name == "continuation-depth") {
        c.continuation_depth = std::uint32_t(std::stoul(value));
      } else if (axes[a].name == "survival") {
        if (value != "off") c.survival = value;
      } else if (axes[a].name == "path-graph") {
        if (value != "off") c.path_graph = value;
      } else if (axes[a].name == "cache-resolution") {
        c.cache_resolution = std::stoi(value);
      } else if (axes[a].name == "cache-store") {
        c.cache_store = std::uint32_t(std::stoul(value));
      } else if (axes[a].name == "cache-length") {
        c.cache_length = std::uint32_t(std::stoul(value));
      } else if (axes[a].name == "cache-update") {
        c.cache_update = value;
      } else if (axes[a].name == "method") {
        c.method = value;
      } else if (axes[a].name == "backend") {
        c.backend = value;
      } else {
        c.filter.emplace_back(axes[a].name, value);
      }
    }
    // What the method ignores does not make another configuration.
    if (!c.UsesBackend()) c.backend = "-";
    if (c.method == "pt") c.filter.clear();
    if (c.Transports()) c.max_depth.reset();  // their paths end where their filtered vertices say
    if (!c.Transports()) c.filtered_vertices.reset();
    if (c.method != "anhpsf") c.continuation_depth.reset();
    if (c.method != "hpsf") c.survival.reset();
    if (c.method != "hpsf") c.path_graph.reset();
    if (c.method != "hashcache") {
      c.cache_resolution.reset();
      c.cache_store.reset();
      c.cache_length.reset();
      c.cache_update.reset();
    }
    if (c.method == "hashcache") c.max_depth.reset();  // its paths have l_store + l_len vertices
    c.id = "method=" + c.method + " backend=" + c.backend + " spp=" + std::to_string(c.spp);
    if (c.frames != 1) c.id += " frames=" + std::to_string(c.frames);
    if (c.max_depth) c.id += " max-depth=" + std::to_string(*c.max_depth);
    if (c.filtered_vertices) c.id += " filtered-vertices=" + std::to_string(*c.filtered_vertices);
    if (c.continuation_depth) c.id += " continuation-depth=" + std::to_string(*c.continuation_depth);
    if (c.survival) c.id += " survival=" + *c.survival;
    if (c.path_graph) c.id += " path-graph=" + *c.path_graph;
    if (c.cache_resolution) c.id += " cache-resolution=" + std::to_string(*c.cache_resolution);
    if (c.cache_store) c.id += " cache-store=" + std::to_string(*c.cache_store);
    if (c.cache_length) c.id += " cache-length=" + std::to_string(*c.cache_length);
    if (c.cache_update) c.id += " cache-update=" + *c.cache_update;
    for (const auto& [name, value] : c.filter) c.id += " " + name + "=" + value;
    if (seen.insert(c.id).second) configs.push_back(std::move(c));
    std::size_t a = axes.size();
    while (a > 0 && ++at[a - 1] == axes[a - 1].values.size()) at[--a] = 0;
    if (a == 0) return configs;
  }
}

}  // namespace hpsf
