#include "core/filter_config.h"

#include <bit>
#include <charconv>
#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "core/shared/fixed_point.h"
#include "core/shared/float_bits.h"
#include "core/shared/full_key.h"
#include "core/shared/levels.h"

namespace hpsf {
namespace {

bool IsPositiveNormalFloat(float x) { return std::isnormal(x) && x > 0.0f; }

}  // namespace

std::string NormalKey::ToString() const {
  switch (mode) {
    case NormalMode::kNone:
      return "none";
    case NormalMode::kSign:
      return "sign";
    case NormalMode::kOctahedral:
      return "octahedral:" + std::to_string(octahedral_bits);
  }
  return "?";
}

NormalKey ParseNormalKey(const std::string& text) {
  if (text == "none") return {NormalMode::kNone, 0};
  if (text == "sign") return {NormalMode::kSign, 0};
  const std::string prefix = "octahedral:";
  if (text.rfind(prefix, 0) == 0) {
    const char* first = text.data() + prefix.size();
    const char* last = text.data() + text.size();
    std::uint32_t bits = 0;
    auto [end, error] = std::from_chars(first, last, bits);
    if (error == std::errc() && end == last && first != last && bits >= 1 && bits <= 16) {
      return {NormalMode::kOctahedral, bits};
    }
    throw ConfigError("--normal", "octahedral needs 1..16 bits per axis, as in octahedral:4; got '" + text + "'");
  }
  throw ConfigError("--normal", "expected none, sign or octahedral:B; got '" + text + "'");
}

void FilterConfig::Validate() const {
  if (!(std::isfinite(filter_width_px) && filter_width_px > 0.0f)) {
    throw ConfigError("--filter-width",
                      "must be a positive finite number of pixels; got " + FormatFloat(filter_width_px));
  }
  if (!(std::isfinite(jitter_scale) && jitter_scale >= 0.0f)) {
    throw ConfigError("--jitter", "must be finite and >= 0; got " + FormatFloat(jitter_scale));
  }
  if (normal.mode == NormalMode::kOctahedral && (normal.octahedral_bits < 1 || normal.octahedral_bits > 16)) {
    throw ConfigError("--normal",
                      "octahedral needs 1..16 bits per axis; got " + std::to_string(normal.octahedral_bits));
  }
  if (!IsPositiveNormalFloat(cell_size)) {
    throw ConfigError("--cell-size",
                      "must be a positive normal float (its inverse must be finite); got " + FormatFloat(cell_size));
  }
  if (!IsPositiveNormalFloat(1.0f / cell_size)) {
    throw ConfigError("--cell-size", "its inverse is not a normal float; got " + FormatFloat(cell_size));
  }
  if (level_min < shared::kMinLevel || level_min > shared::kMaxLevel) {
    throw ConfigError("--level-min", "must lie in [-126, 126]; got " + std::to_string(level_min));
  }
  if (level_max < shared::kMinLevel || level_max > shared::kMaxLevel) {
    throw ConfigError("--level-max", "must lie in [-126, 126]; got " + std::to_string(level_max));
  }
  if (level_min > level_max) {
    throw ConfigError("--level-min", "must not exceed --level-max (" + std::to_string(level_max) + "); got " +
                                         std::to_string(level_min));
  }
  if (capacity == 0 || !std::has_single_bit(capacity) || capacity > (1u << 31)) {
    throw ConfigError("--capacity", "must be a power of two in [1, 2^31]; got " + std::to_string(capacity));
  }
  if (probe_limit == 0 || probe_limit > capacity) {
    throw ConfigError("--probe-limit", "must lie in [1, capacity = " + std::to_string(capacity) + "]; got " +
                                           std::to_string(probe_limit));
  }
  if (probing == ProbeKind::kBucket && !std::has_single_bit(probe_limit)) {
    throw ConfigError("--probing", "bucket:B aligns its buckets to B, which must be a power of two; got B = " +
                                       std::to_string(probe_limit));
  }
  if (fingerprint_bits < 8 || fingerprint_bits > 32) {
    throw ConfigError("--fingerprint-bits", "must lie in [8, 32]; got " + std::to_string(fingerprint_bits));
  }
  if (key_identity == KeyIdentity::kFull && fingerprint_bits != 32) {
    throw ConfigError("--fingerprint-bits", "a full key (--key-identity full) stores no fingerprint; got " +
                                                std::to_string(fingerprint_bits) + " bits");
  }
  if (key_identity == KeyIdentity::kFull && normal.mode == NormalMode::kOctahedral && normal.octahedral_bits > 1) {
    throw ConfigError("--normal",
                      "a full key keeps 3 bits of normal bucket, so octahedral:1 at most; got " + normal.ToString());
  }
  if (fixed_point_bits &&
      (*fixed_point_bits < shared::kFixedPointBitsMin || *fixed_point_bits > shared::kFixedPointBitsMax)) {
    throw ConfigError("--fixed-point-bits", "must lie in [" + std::to_string(shared::kFixedPointBitsMin) + ", " +
                                                std::to_string(shared::kFixedPointBitsMax) + "]; got " +
                                                std::to_string(*fixed_point_bits));
  }
  if (square_bits && (*square_bits < shared::kFixedPointBitsMin || *square_bits > shared::kFixedPointBitsMax)) {
    throw ConfigError("--square-bits", "must lie in [" + std::to_string(shared::kFixedPointBitsMin) + ", " +
                                           std::to_string(shared::kFixedPointBitsMax) + "]; got " +
                                           std::to_string(*square_bits));
  }
  if (square_bits && !second_moments) {
    throw ConfigError("--square-bits", "is G of the square sums, which need --second-moments on");
  }
  if (frames < 1 || frames > kMaxFrames) {
    throw ConfigError("--frames", "must lie in [1, " + std::to_string(kMaxFrames) + "]; got " + std::to_string(frames));
  }
  if (ParseEviction(eviction.ToString()) != eviction) {
    throw ConfigError("--eviction", "is not a policy: " + eviction.ToString() + " with " +
                                        std::to_string(eviction.unseen_frames) + " frames unseen");
  }
  if (eviction.by_priority() && key_identity == KeyIdentity::kFingerprint && fingerprint_bits > 31) {
    throw ConfigError("--eviction",
                      "priority reserves the tag 0xFFFFFFFF for its tombstones, so it needs "
                      "--fingerprint-bits 31 or fewer; got " +
                          std::to_string(fingerprint_bits));
  }
  if (ParseLevelSeed(level_seed.ToString()) != level_seed) {
    throw ConfigError("--level-change", "is not a mode: " + level_seed.ToString());
  }
  if (level_seed.enabled && !lod) {
    throw ConfigError("--level-change", "seeds cells across levels, which needs --lod on");
  }
  // Forcing runs a pass the options ask for where the plan skips it; a pass not asked for has nothing to run.
  if (forced.Has(Effect::kTemporal) && !temporal.blends()) {
    throw ConfigError("--force-effect", "temporal needs a blending --temporal (ema or adaptive)");
  }
  if (forced.Has(Effect::kLevelSeed) && !level_seed.enabled) {
    throw ConfigError("--force-effect", "level-seed needs --level-change seed");
  }
  if (forced.Has(Effect::kEviction) && !eviction.enabled()) {
    throw ConfigError("--force-effect", "eviction needs an --eviction policy");
  }
  if (forced.Has(Effect::kNeighbourSearch) && !neighbour_search) {
    throw ConfigError("--force-effect", "neighbour-search needs --neighbour-search on");
  }
  if (forced.Has(Effect::kTransport) && !transport) {
    throw ConfigError("--force-effect", "transport needs --transport on");
  }
  if (forced.Has(Effect::kSurvival) && !survival.enabled()) {
    throw ConfigError("--force-effect", "survival needs --survival linear:... or smooth:...");
  }
  if (forced.Has(Effect::kPathGraph) && !path_graph.enabled) {
    throw ConfigError("--force-effect", "path-graph needs --path-graph with a bound");
  }
  if (ParseTemporal(temporal.ToString()) != temporal) {
    throw ConfigError("--temporal", "is not a mode: " + temporal.ToString());
  }
  // packed-decimal sums are at their own scale.
  if (accumulation == Accumulation::kPackedDecimal && fixed_point_bits) {
    throw ConfigError("--fixed-point-bits", "applies to fixed64; packed-decimal sums are at the scale 1000");
  }
  if (levels < 1 || levels > shared::kMaxLevels) {
    throw ConfigError("--levels",
                      "must lie in [1, " + std::to_string(shared::kMaxLevels) + "]; got " + std::to_string(levels));
  }
  if (min_count < 1) throw ConfigError("--min-count", "must be >= 1; got " + std::to_string(min_count));
  if (min_count > 1 && levels == 1 && !neighbour_search) {
    throw ConfigError("--min-count",
                      "chooses among a record's levels or starts a search, which needs --levels 2 or more or "
                      "--neighbour-search");
  }
  if (second_moments && accumulation == Accumulation::kPackedDecimal) {
    throw ConfigError("--second-moments", "needs fixed64 or float32 sums; packed-decimal keeps no room for squares");
  }
  if (second_moments && level_seed.enabled) {
    throw ConfigError("--second-moments",
                      "cannot be kept with --level-change seed: a seed carries sums and counts only");
  }
  if (survival.enabled() && !second_moments) {
    throw ConfigError("--survival", "reads each cell's variance, which needs --second-moments on");
  }
  if (path_graph.enabled && !second_moments) {
    throw ConfigError("--path-graph", "reads each cell's variance, which needs --second-moments on");
  }
  if (path_graph.enabled && transport) {
    throw ConfigError("--path-graph",
                      "gives a pixel's own light; it is not built with --transport on, whose records carry one "
                      "bounce each");
  }
  if (temporal.mode == TemporalMode::kAdaptiveVariance && !second_moments) {
    throw ConfigError("--temporal", "adaptive-variance reads each cell's variance, which needs --second-moments on");
  }
  if (interpolation.enabled() && !second_moments) {
    throw ConfigError("--interpolation", "reads each cell's variance, which needs --second-moments on");
  }
  if (interpolation.enabled() && neighbour_search) {
    throw ConfigError("--interpolation",
                      "weighs the variance of a record's own cell; it is not built with --neighbour-search, whose "
                      "stencil reads several");
  }
  if (survival.enabled() && transport) {
    throw ConfigError("--survival", "decides at a path's primary vertex; it is not built with --transport on");
  }
  if (neighbour_search && min_count == 1) {
    throw ConfigError("--neighbour-search", "searches cells below --min-count, which needs --min-count 2 or more");
  }
}

namespace {

std::uint32_t Headroom(std::uint32_t frames, double weight) {
  const double headroom = double(frames) * std::ceil(weight);
  return headroom >= 4294967295.0 ? 0xFFFFFFFFu : std::uint32_t(headroom);
}

}  // namespace

std::uint32_t FilterConfig::SumHeadroom() const {
  return Headroom(frames, survival.enabled() ? 1.0 / survival.floor : 1.0);
}

std::uint32_t FilterConfig::SquareHeadroom() const {
  return Headroom(frames, survival.enabled() ? 1.0 / (survival.floor * survival.floor) : 1.0);
}

std::string FilterConfig::ToString() const {
  return "[ FilterConfig filter_width_px: " + FormatFloat(filter_width_px) +
         " jitter_scale: " + FormatFloat(jitter_scale) + " normal: " + normal.ToString() +
         " normal_in_index: " + (normal_in_index ? "true" : "false") + " lod: " + (lod ? "on" : "off") +
         " cell_size: " + FormatFloat(cell_size) + " level: [" + std::to_string(level_min) + ", " +
         std::to_string(level_max) + "] accum: " + hpsf::ToString(accumulation) +
         " capacity: " + std::to_string(capacity) + " probe_limit: " + std::to_string(probe_limit) +
         // Only when not linear, so configs of hpsf's own table read as they always have (golden metadata).
         (probing != ProbeKind::kLinear ? " probing: " + hpsf::ToString(probing) : std::string()) +
         " fingerprint_bits: " + std::to_string(fingerprint_bits) +
         (key_identity != KeyIdentity::kFingerprint ? " key_identity: " + hpsf::ToString(key_identity)
                                                    : std::string()) +
         " seed: " + std::to_string(seed) + " frame: " + std::to_string(frame) +
         // Only when set, so single-frame configs read as they always have (golden metadata holds them).
         (fixed_point_bits ? " fixed_point_bits: " + std::to_string(*fixed_point_bits) : std::string()) +
         (square_bits ? " square_bits: " + std::to_string(*square_bits) : std::string()) +
         (frames != 1 ? " frames: " + std::to_string(frames) : std::string()) +
         (eviction.enabled() ? " eviction: " + eviction.ToString() : std::string()) +
         (temporal.blends() ? " temporal: " + temporal.ToString() : std::string()) +
         (level_seed.enabled ? " level_change: " + level_seed.ToString() : std::string()) +
         (compaction != Compaction::kNone ? " compaction: " + hpsf::ToString(compaction) : std::string()) +
         (levels != 1 ? " levels: " + std::to_string(levels) : std::string()) +
         (min_count != 1 ? " min_count: " + std::to_string(min_count) : std::string()) +
         (neighbour_search ? " neighbour_search: on" : std::string()) + (transport ? " transport: on" : std::string()) +
         (second_moments ? " second_moments: on" : std::string()) +
         (survival.enabled() ? " survival: " + survival.ToString() : std::string()) +
         (path_graph.enabled ? " path_graph: " + path_graph.ToString() : std::string()) +
         (interpolation.enabled() ? " interpolation: " + interpolation.ToString() : std::string()) +
         (forced.Any() ? " force_effect: " + forced.ToString() : std::string()) + " ]";
}

shared::KeyParams MakeKeyParams(const FilterConfig& config, float footprint_scale, std::uint32_t record_count) {
  config.Validate();
  if (!(std::isfinite(footprint_scale) && footprint_scale >= 0.0f)) {
    throw ConfigError("--filter-width",
                      "gives a footprint scale that is not finite and >= 0: " + FormatFloat(footprint_scale));
  }
  shared::KeyParams p{};
  p.footprint_scale = footprint_scale;
  p.jitter_scale = config.jitter_scale;
  p.cell_size = config.cell_size;
  p.inverse_cell_size = 1.0f / config.cell_size;  // correctly rounded on the host
  p.level_min = config.level_min;
  p.level_max = config.level_max;
  p.lod_enabled = config.lod ? 1u : 0u;
  p.normal_mode = config.normal.mode == NormalMode::kNone   ? shared::kNormalNone
                  : config.normal.mode == NormalMode::kSign ? shared::kNormalSign
                                                            : shared::kNormalOctahedral;
  p.normal_bits = config.normal.octahedral_bits;
  p.normal_in_index = config.normal_in_index ? 1u : 0u;
  p.capacity_mask = config.capacity - 1u;
  p.fingerprint_bits = config.fingerprint_bits;
  p.seed = config.seed;
  p.frame = config.frame;
  p.record_count = record_count;
  p.key_identity = config.key_identity == KeyIdentity::kFull ? shared::kIdentityFull : shared::kIdentityFingerprint;
  return p;
}

}  // namespace hpsf
