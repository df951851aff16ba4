#include "core/backend.h"

#include <string>

#include "core/error.h"

namespace hpsf {

void Backend::Reset() {
  ForgetTable();
  sequence_.reset();
  frames_filtered_ = 0;
}

const Image& Backend::FilterFrame(const RecordBatch& batch, const FilterConfig& config) {
  config.Validate();
  const bool first = !sequence_;
  if (!first) CheckSameSequence(*sequence_, config);
  const Image& image = FilterFrameInto(batch, config, frames_filtered_);
  if (first) sequence_ = config;  // only once the first frame has gone in: a failed one leaves the table empty
  ++frames_filtered_;
  return image;
}

void CheckSameSequence(const FilterConfig& first, const FilterConfig& next) {
  auto require = [](bool same, const char* option) {
    if (!same) throw ConfigError(option, "changed within a sequence of frames: one table cannot carry on across it");
  };
  require(first.filter_width_px == next.filter_width_px, "--filter-width");
  require(first.jitter_scale == next.jitter_scale, "--jitter");
  require(first.normal.ToString() == next.normal.ToString(), "--normal");
  require(first.normal_in_index == next.normal_in_index, "--normal-in-fingerprint-only");
  require(first.lod == next.lod, "--lod");
  require(first.cell_size == next.cell_size, "--cell-size");
  require(first.level_min == next.level_min, "--level-min");
  require(first.level_max == next.level_max, "--level-max");
  require(first.accumulation == next.accumulation, "--accum");
  require(first.capacity == next.capacity, "--capacity");
  require(first.probe_limit == next.probe_limit, "--probe-limit");
  require(first.probing == next.probing, "--probing");
  require(first.fingerprint_bits == next.fingerprint_bits, "--fingerprint-bits");
  require(first.key_identity == next.key_identity, "--key-identity");
  require(first.seed == next.seed, "--seed");
  require(first.fixed_point_bits == next.fixed_point_bits, "--fixed-point-bits");
  require(first.frames == next.frames, "--frames");
  require(first.eviction == next.eviction, "--eviction");
  require(first.temporal == next.temporal, "--temporal");
  require(first.forced == next.forced, "--force-effect");
  require(first.levels == next.levels, "--levels");
  require(first.min_count == next.min_count, "--min-count");
  require(first.neighbour_search == next.neighbour_search, "--neighbour-search");
  require(first.transport == next.transport, "--transport");
}

}  // namespace hpsf
