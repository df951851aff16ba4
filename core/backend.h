// The one interface of a backend (docs/design/README.md): a backend owns its table from frame to frame. Reset empties
// it; FilterFrame adds one frame's records to it and resolves that frame against it. This is temporal
// integration (Binder et al. §3.4.1): a cell's sums and count are those of every frame since Reset, so its average
// weighs old and new samples by their counts, alpha = N_old / (N_old + N_new).
//
// F, the fraction bits of fixed64, is chosen by the first frame for config.frames frames like it (or given by
// config.fixed_point_bits) and kept: sums of different F cannot be added. Nothing that shapes the table or the
// keys may change within a sequence, only the frame number (a ConfigError names what changed).
//
// What tools need of a frame comes through this interface alone: the exact result (the reference), the hashed run
// (a hashed backend's table dump, keys and placements), and where the frame's time went, in milliseconds on every
// backend. Which backends exist, and how each is made, is core/backend_registry.h.
#ifndef HPSF_CORE_BACKEND_H
#define HPSF_CORE_BACKEND_H

#include <cstdint>
#include <optional>
#include <string>

#include "core/filter_config.h"
#include "core/filter_result.h"
#include "core/hashed_run.h"
#include "core/image.h"
#include "core/record.h"

namespace hpsf {

// A frame's wall time in milliseconds, grouped alike on every backend. No output bit depends on it.
struct FrameTimings {
  double transport_ms = 0;        // several filtered bounces' lookups in the table before the frame (core/transport.h)
  std::optional<double> keys_ms;  // keys, input checks and the choice of F; absent where the accumulate computes keys
  double accumulate_ms = 0;       // clearing or preparing the table and the adds
  double level_seed_ms = 0;       // the seed pass of resolution changes (core/level_seed.h)
  double compaction_ms = 0;       // the gather into the occupied list (core/compaction.h)
  double settle_ms = 0;           // packed-decimal's settle: frame counters and halving (core/shared/packed_sums.h)
  double temporal_ms = 0;         // the temporal blend (core/temporal.h)
  double eviction_ms = 0;         // the evict and reclaim passes (core/eviction.h)
  double resolve_ms = 0;          // the table's dump and the resolve into pixels
  std::optional<double> transfer_ms;  // copies between host and device; absent where there is no device
};

class Backend {
 public:
  virtual ~Backend() = default;

  // "reference", "emulated" or "vulkan".
  virtual std::string Name() const = 0;

  // Forgets the table: the next frame starts a sequence with an empty one.
  void Reset();

  // Filters one frame's records into the table and returns the frame's image.
  const Image& FilterFrame(const RecordBatch& batch, const FilterConfig& config);

  // A hashed backend's last frame (its table after the frame, and each record's key and placement), what the
  // table checker and the cross-check judge; null for the reference, whose table is the exact map, and before a
  // frame.
  virtual const HashedRun* LastHashedRun() const { return nullptr; }
  // The reference's last frame: the exact map's cells and each record's placement; null for a hashed backend.
  virtual const FilterResult* LastExactResult() const { return nullptr; }
  // Where the last frame's time went; all zero for the reference, which times nothing.
  virtual FrameTimings LastFrameTimings() const { return {}; }

  // Frames filtered since Reset.
  std::uint32_t frames_filtered() const { return frames_filtered_; }

 protected:
  // index: the frame's place in the sequence. 0: the table is empty (the first frame of a sequence); else the frame
  // adds to the table and keeps F. The frame runs the passes PlanFrameEffects(config, index) plans
  // (core/effect_plan.h).
  virtual const Image& FilterFrameInto(const RecordBatch& batch, const FilterConfig& config, std::uint32_t index) = 0;
  virtual void ForgetTable() = 0;

 private:
  std::optional<FilterConfig> sequence_;  // the first frame's config, frame number aside
  std::uint32_t frames_filtered_ = 0;
};

// Throws ConfigError naming the first option in which `next` differs from `first` other than the frame number: a
// table cannot carry on across such a change.
void CheckSameSequence(const FilterConfig& first, const FilterConfig& next);

}  // namespace hpsf

#endif  // HPSF_CORE_BACKEND_H
