#include "tools/hpsf/filter_options.h"

#include <charconv>
#include <optional>
#include <string>
#include <system_error>

#include "core/error.h"
#include "verifier/gate/table_declaration.h"

namespace hpsf {

void AddFilterOptions(CLI::App& command, FilterOptions& o) {
  FilterConfig& c = o.config;
  o.command = &command;
  command.add_flag("--no-filter", o.no_filter, "Plain path tracing: each sample keeps its own contribution");
  command.add_flag("--variance", o.variance,
                   "Also write each pixel's variance (channels variance.R/G/B), each 8x8 tile's (tile_variance.R/G/B) "
                   "and the image mean's; needs 2+ spp (diff --statistical: 4+)");
  command.add_option("--filter-width", c.filter_width_px, "Cell size in pixels at a primary hit")
      ->capture_default_str();
  command.add_option("--jitter", c.jitter_scale, "Jitter amplitude in cells (0: off)")->capture_default_str();
  command.add_option("--normal", o.normal, "Normal key: none, sign or octahedral:B")->capture_default_str();
  command.add_flag("!--normal-in-fingerprint-only", c.normal_in_index, "Keep the normal bucket out of the index hash");
  command.add_option("--lod", o.lod, "Level of detail from the path length: on or off")->capture_default_str();
  command.add_option("--cell-size", c.cell_size, "Cell edge when --lod off")->capture_default_str();
  command.add_option("--level-min", c.level_min, "Smallest level, in [-126, 126]")->capture_default_str();
  command.add_option("--level-max", c.level_max, "Largest level, in [-126, 126]")->capture_default_str();
  command
      .add_option("--accum", o.accumulation,
                  "Accumulation: fixed64, float32 or packed-decimal (SHaRC's 32-bit sums at 1000)")
      ->capture_default_str();
  command.add_option("--seed", c.seed, "Seed of every random number")->capture_default_str();
  command.add_option("--capacity", c.capacity, "Hash table slots (a power of two)")->capture_default_str();
  o.probe_limit_option =
      command.add_option("--probe-limit", c.probe_limit, "Slots a key may occupy: W of linear, B of the buckets")
          ->capture_default_str();
  command
      .add_option("--probing", o.probing,
                  "The order of a key's slots: linear (from its home slot, wrapping), bucket (the aligned bucket of "
                  "--probe-limit slots that holds it; a power of two) or bucket-window (--probe-limit slots from "
                  "min(home, capacity - size), never wrapping); KIND:N sets the size too")
      ->capture_default_str();
  command.add_option("--table", o.table,
                     "A table declaration (JSON): its probing, key identity, sums and passes, each in place of the "
                     "option it stands for (docs/reference/table-declaration.md)");
  command.add_option("--fingerprint-bits", c.fingerprint_bits, "Fingerprint width, 8..32")->capture_default_str();
  command
      .add_option("--key-identity", o.key_identity,
                  "What a slot stores to tell keys apart: fingerprint (--fingerprint-bits of a hash, 32-bit tags) or "
                  "full (the whole key, 64-bit tags: no two cells share a slot; cells within 2^16 of the origin per "
                  "axis, normals at most 3 bits)")
      ->capture_default_str();
  command
      .add_option("--fixed-point-bits", o.fixed_point_bits,
                  "F, fixed64's fraction bits, in [-126, 126]; auto: the largest the first frame's totals allow")
      ->capture_default_str();
  command
      .add_option("--square-bits", o.square_bits,
                  "G, the fraction bits of the square sums (--second-moments), in [-126, 126]; auto: chosen as F is "
                  "(a repro bundle of a run with --survival gives the run's)")
      ->capture_default_str();
  command
      .add_option("--eviction", o.eviction,
                  "Cells a table kept across frames forgets after each frame: none, strict (not touched this frame) "
                  "stale:N (not touched for N frames) or priority (under pressure: in the window of a record that "
                  "found no slot, the least recently seen, least sampled cell; needs --fingerprint-bits 31 or fewer)")
      ->capture_default_str();
  command
      .add_option("--temporal", o.temporal,
                  "How a cell kept across frames blends its history with a frame: integrate (by counts), "
                  "ema:ALPHA[:MAXCOUNT] (history weight at most ALPHA, its count at most MAXCOUNT), adaptive "
                  "(integration, less where the cell's light changed) or adaptive-variance (adaptive, taking a change "
                  "within two standard deviations of the noise the cell's variance predicts for noise; needs "
                  "--second-moments on)")
      ->capture_default_str();
  command
      .add_option("--level-change", o.level_change,
                  "How a cell new in a frame starts when its location's level changed: none (empty) or seed[:S] "
                  "(from its children's sums one level finer, else an eighth of its parent's, times 2^-S)")
      ->capture_default_str();
  command
      .add_option("--compaction", o.compaction,
                  "How the passes over slots (temporal blend, eviction) find them: none (every slot of the table) or "
                  "occupied-list (a list of the occupied slots kept beside the table, so they cost in proportion to "
                  "those)")
      ->capture_default_str();
  command
      .add_option("--levels", c.levels,
                  "Multi-level accumulation: each record is added to its own cell and the LEVELS - 1 coarser cells "
                  "that hold it (each twice the edge of the one below, nested exactly), 1..8")
      ->capture_default_str();
  command
      .add_option("--min-count", c.min_count,
                  "The resolve reads a record's finest level whose count reaches this, else its coarsest "
                  "(needs --levels 2 or more, or --neighbour-search)")
      ->capture_default_str();
  command
      .add_option("--neighbour-search", o.neighbour_search,
                  "on or off: a record whose chosen cell holds fewer than --min-count samples also reads the 2^3 "
                  "cells of its level nearest its jittered position, found by lookup, and averages them by count")
      ->capture_default_str();
  command
      .add_option("--transport", o.transport,
                  "on or off: several filtered bounces (nHPSF): from a sequence's second frame on, each record whose "
                  "path scattered to a further vertex adds the light the table before the frame holds at that "
                  "vertex's cell, times its transport weight, so K frames hold up to K + 1 bounces (a scene is "
                  "traced with its scattered vertices; a record file must carry them)")
      ->capture_default_str();
  command
      .add_option("--second-moments", o.second_moments,
                  "on or off: each slot also keeps the sum of its records' squared brightness (r + g + b)^2, so the "
                  "table holds each cell's variance (fixed64 at a scale 2^G of its own, exact; float32 as floats)")
      ->capture_default_str();
  command
      .add_option("--interpolation", o.interpolation,
                  "Variance-aware cell interpolation (Schipek eqs. 4.4, 4.5): off, path, step:V0:V1 or smooth:V0:V1. "
                  "The resolve gives each record w times its cell's average plus 1 - w times its own light, w a "
                  "function of the cell's variance: the cell outside [V0, V1], the path inside (step), or leaning to "
                  "it (smooth); path: w = 0, each record's own light (a path graph's). Needs --second-moments on")
      ->capture_default_str();
  command.add_option("--force-effect", o.force_effects,
                     "Run this effect where the plan skips it as a no-op (animation, temporal, level-seed, "
                     "eviction, neighbour-search, transport, survival; repeatable): the same bits, at the pass's "
                     "cost");
}

namespace {

// "auto" (unset) or an integer, for --fixed-point-bits and --square-bits.
std::optional<int> AutoOrInteger(const char* option, const std::string& text) {
  if (text == "auto") return std::nullopt;
  int bits = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, bits);
  if (error != std::errc() || stop != end) {
    throw ConfigError(option, "expected auto or an integer; got '" + text + "'");
  }
  return bits;
}

}  // namespace

FilterConfig ResolveFilterConfig(const FilterOptions& o) {
  FilterConfig config = o.config;
  config.normal = ParseNormalKey(o.normal);
  config.accumulation = ParseAccumulation(o.accumulation);
  if (o.lod != "on" && o.lod != "off") throw ConfigError("--lod", "expected on or off; got '" + o.lod + "'");
  config.lod = o.lod == "on";
  if (o.neighbour_search != "on" && o.neighbour_search != "off") {
    throw ConfigError("--neighbour-search", "expected on or off; got '" + o.neighbour_search + "'");
  }
  config.neighbour_search = o.neighbour_search == "on";
  if (o.transport != "on" && o.transport != "off") {
    throw ConfigError("--transport", "expected on or off; got '" + o.transport + "'");
  }
  config.transport = o.transport == "on";
  if (o.second_moments != "on" && o.second_moments != "off") {
    throw ConfigError("--second-moments", "expected on or off; got '" + o.second_moments + "'");
  }
  config.second_moments = o.second_moments == "on";
  config.interpolation = ParseInterpolation(o.interpolation);
  config.fixed_point_bits = AutoOrInteger("--fixed-point-bits", o.fixed_point_bits);
  config.square_bits = AutoOrInteger("--square-bits", o.square_bits);
  const Probing probing = ParseProbing(o.probing);
  config.probing = probing.kind;
  if (probing.size) {
    if (o.probe_limit_option != nullptr && o.probe_limit_option->count() > 0 && *probing.size != config.probe_limit) {
      throw ConfigError("--probing", "gives the size " + std::to_string(*probing.size) + " and --probe-limit gives " +
                                         std::to_string(config.probe_limit) + ": give it once");
    }
    config.probe_limit = *probing.size;
  }
  config.eviction = ParseEviction(o.eviction);
  config.level_seed = ParseLevelSeed(o.level_change);
  config.temporal = ParseTemporal(o.temporal);
  config.compaction = ParseCompaction(o.compaction);
  config.key_identity = ParseKeyIdentity(o.key_identity);
  for (const std::string& name : o.force_effects) config.forced.Add(ParseEffect(name));
  if (!o.table.empty()) {
    for (const DeclaredSetting& d : ApplyTableDeclaration(o.table, config)) {
      for (const std::string& option : d.option == "--probing" ? std::vector<std::string>{"--probing", "--probe-limit"}
                                                               : std::vector<std::string>{d.option}) {
        const CLI::Option* given = o.command != nullptr ? o.command->get_option_no_throw(option) : nullptr;
        if (given != nullptr && given->count() > 0) {
          throw ConfigError(
              "--table", o.table + " declares " + d.pointer + ", which " + option + " gives too: give it in one place");
        }
      }
    }
  }
  config.Validate();
  return config;
}

void CheckVarianceSamples(const FilterOptions& o, std::uint32_t samples_per_pixel, const std::string& source) {
  if (o.variance && samples_per_pixel < 2) {
    throw ConfigError("--variance", "needs 2 or more samples per pixel to see a pixel's spread; " + source + " has " +
                                        std::to_string(samples_per_pixel));
  }
}

nlohmann::json ToJson(const FilterConfig& c) {
  return {{"filter_width_px", c.filter_width_px},
          {"jitter", c.jitter_scale},
          {"normal", c.normal.ToString()},
          {"normal_in_index", c.normal_in_index},
          {"lod", c.lod},
          {"cell_size", c.cell_size},
          {"level_min", c.level_min},
          {"level_max", c.level_max},
          {"accum", ToString(c.accumulation)},
          {"capacity", c.capacity},
          {"probe_limit", c.probe_limit},
          {"probing", ToString(c.probing)},
          {"fingerprint_bits", c.fingerprint_bits},
          {"key_identity", ToString(c.key_identity)},
          {"seed", c.seed},
          {"frame", c.frame},
          {"frames", c.frames},
          {"eviction", c.eviction.ToString()},
          {"level_change", c.level_seed.ToString()},
          {"temporal", c.temporal.ToString()},
          {"compaction", ToString(c.compaction)},
          {"levels", c.levels},
          {"min_count", c.min_count},
          {"neighbour_search", c.neighbour_search},
          {"transport", c.transport},
          {"second_moments", c.second_moments},
          {"survival", c.survival.ToString()},
          {"path_graph", c.path_graph.ToString()},
          {"interpolation", c.interpolation.ToString()},
          {"force_effect", c.forced.ToString()},
          {"fixed_point_bits", c.fixed_point_bits ? nlohmann::json(*c.fixed_point_bits) : nlohmann::json("auto")},
          {"square_bits", c.square_bits ? nlohmann::json(*c.square_bits) : nlohmann::json("auto")}};
}

}  // namespace hpsf
