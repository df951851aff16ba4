// The oracle: hashed path space filtering with exact keys. Records are keyed by core/shared/key.h and grouped
// in an ordered map from the six full key words to a cell: no hashing into slots, no fingerprints, no probing,
// so nothing can collide, alias or fail. Single-threaded, in record order; obviously correct, never fast.
#ifndef HPSF_REFERENCE_REFERENCE_FILTER_H
#define HPSF_REFERENCE_REFERENCE_FILTER_H

#include "core/effect_plan.h"
#include "core/filter_config.h"
#include "core/filter_result.h"
#include "core/record.h"

namespace hpsf {

// previous: the result of the frames before this one in a sequence (core/backend.h), whose cells this frame adds
// to and whose F it keeps; null for a table of this batch alone. The result's placement and per-record counts are
// this frame's; its cells are the whole table. effects: the passes the frame runs (core/effect_plan.h); null plans
// them for the first frame or, with `previous`, for a later one.
FilterResult ReferenceFilter(const RecordBatch& batch, const FilterConfig& config,
                             const FilterResult* previous = nullptr, const FrameEffects* effects = nullptr);

// Plain path tracing from the same batch: each record's own radiance_before + throughput * contribution.
Image UnfilteredImage(const RecordBatch& batch);

}  // namespace hpsf

#endif  // HPSF_REFERENCE_REFERENCE_FILTER_H
