// The oracle: hashed path space filtering with exact keys. Records are keyed by core/shared/key.h and grouped
// in an ordered map from the six full key words to a cell: no hashing into slots, no fingerprints, no probing,
// so nothing can collide, alias or fail. Single-threaded, in record order; obviously correct, never fast.
#ifndef HPSF_REFERENCE_REFERENCE_FILTER_H
#define HPSF_REFERENCE_REFERENCE_FILTER_H

#include "core/filter_config.h"
#include "core/filter_result.h"
#include "core/record.h"

namespace hpsf {

FilterResult ReferenceFilter(const RecordBatch& batch, const FilterConfig& config);

// Plain path tracing from the same batch: each record's own radiance_before + throughput * contribution.
Image UnfilteredImage(const RecordBatch& batch);

}  // namespace hpsf

#endif  // HPSF_REFERENCE_REFERENCE_FILTER_H
