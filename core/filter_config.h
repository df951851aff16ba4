// Every option of the filter, validated as a whole: a bad value is a ConfigError that names the option.
#ifndef HPSF_CORE_FILTER_CONFIG_H
#define HPSF_CORE_FILTER_CONFIG_H

#include <cstdint>
#include <optional>
#include <string>

#include "core/accumulation.h"
#include "core/cell_interpolation.h"
#include "core/compaction.h"
#include "core/effect_plan.h"
#include "core/eviction.h"
#include "core/key_identity.h"
#include "core/level_seed.h"
#include "core/path_graph.h"
#include "core/probing.h"
#include "core/shared/key_params.h"
#include "core/survival.h"
#include "core/temporal.h"

namespace hpsf {

enum class NormalMode { kNone, kSign, kOctahedral };

struct NormalKey {
  NormalMode mode = NormalMode::kSign;
  std::uint32_t octahedral_bits = 0;  // per axis, 1..16, octahedral only
  std::string ToString() const;       // "none", "sign", "octahedral:4"
};

// Parses "none", "sign" or "octahedral:B"; a ConfigError naming --normal otherwise.
NormalKey ParseNormalKey(const std::string& text);

inline constexpr std::uint32_t kMaxFrames = 1u << 20;  // --frames

struct FilterConfig {
  float filter_width_px = 4.0f;  // --filter-width: a cell spans this many pixels at a primary hit
  float jitter_scale = 1.0f;     // --jitter: amplitude in units of the cell size; 0 turns jitter off
  NormalKey normal;              // --normal
  bool normal_in_index = true;   // --normal-in-index: false keeps the bucket in the fingerprint only
  bool lod = true;               // --lod on|off
  float cell_size = 1.0f;        // --cell-size: the cell edge when level of detail is off
  int level_min = -126;          // --level-min, --level-max: clamp of the level, inside [-126, 126]
  int level_max = 126;
  Accumulation accumulation = Accumulation::kFixed64;    // --accum
  std::uint32_t capacity = 1u << 22;                     // --capacity: slots, a power of two
  std::uint32_t probe_limit = 16;                        // --probe-limit: slots tried before a probe failure
  ProbeKind probing = ProbeKind::kLinear;                // --probing: the order of the slots tried
  std::uint32_t fingerprint_bits = 32;                   // --fingerprint-bits: 8..32
  KeyIdentity key_identity = KeyIdentity::kFingerprint;  // --key-identity: a fingerprint or the full key per slot
  std::uint32_t seed = 1;                                // --seed
  std::uint32_t frame = 0;                               // in every random number of the key path (the jitter)
  // --fixed-point-bits: F of fixed64 for every frame; unset, the first frame of a table chooses it, leaving room
  // for `frames` frames like it (core/fixed_point_scale.h).
  std::optional<int> fixed_point_bits;
  // --square-bits: G of the square sums (--second-moments) for every frame; unset, chosen as F is
  std::optional<int> square_bits;
  std::uint32_t frames = 1;  // --frames: how many frames one table integrates (core/backend.h)
  Eviction eviction;         // --eviction: which cells the table forgets after each frame (core/eviction.h)
  Temporal temporal;         // --temporal: how a cell blends its history with a frame (core/temporal.h)
  LevelSeed level_seed;      // --level-change: how a cell new at another level starts (core/level_seed.h)
  Compaction compaction = Compaction::kNone;  // --compaction: the passes over slots step a list (core/compaction.h)
  // --levels: a record is added to its own cell and the levels - 1 coarser cells that hold it (core/shared/levels.h)
  std::uint32_t levels = 1;
  // --min-count: the resolve reads a record's finest level whose count reaches it, else the coarsest
  std::uint32_t min_count = 1;
  // --neighbour-search: a record whose chosen cell holds fewer than min_count samples also reads the stencil of cells
  // nearest its jittered position (core/shared/neighbour_search.h)
  bool neighbour_search = false;
  // Several filtered bounces (core/transport.h): from a sequence's second frame on, each record with a scattered
  // vertex adds the previous frame's average at that vertex's cell, carried back by its transport weight
  bool transport = false;
  // --second-moments: each slot also keeps the sum of its records' squared brightness, from which a cell's variance
  // follows (core/shared/second_moment.h)
  bool second_moments = false;
  // --survival: a traced sequence's paths survive their primary vertex by the variance of its cell in the table the
  // frame before left (core/survival.h); the tracer decides, the filter passes see the records it made
  SurvivalParams survival;
  // --path-graph: a traced sequence's paths are cut where the variance they gather along their vertices' cells in the
  // table the frame before left would pass a bound (core/path_graph.h); the tracer decides, as for survival
  PathGraphParams path_graph;
  // --interpolation: the resolve blends each record's own light with its cell's average by a weight of the cell's
  // variance (core/cell_interpolation.h)
  CellInterpolation interpolation;
  ForcedEffects forced;  // --force-effect: passes run where the plan skips them (core/effect_plan.h)

  // The tracer reads the table the frame before left (--survival, --path-graph: core/previous_table_view.h).
  bool TracerReadsTable() const { return survival.enabled() || path_graph.enabled; }

  // The frames of headroom a sequence's first frame leaves when it chooses F and G (core/fixed_point_scale.h):
  // `frames`, times the most a survivor's light can be weighted with --survival (1 / floor; its square for G), so that
  // no later frame's sums or squares outgrow them. Saturates at 2^32 - 1.
  std::uint32_t SumHeadroom() const;
  std::uint32_t SquareHeadroom() const;

  // Throws ConfigError for the first invalid option.
  void Validate() const;
  std::string ToString() const;
};

// The key path's view of a validated config. footprint_scale comes from the camera (core/footprint.h).
shared::KeyParams MakeKeyParams(const FilterConfig& config, float footprint_scale, std::uint32_t record_count);

inline shared::ProbeScheme ProbeSchemeOf(const FilterConfig& config) {
  return MakeProbeScheme(config.probing, config.capacity, config.probe_limit);
}

}  // namespace hpsf

#endif  // HPSF_CORE_FILTER_CONFIG_H
