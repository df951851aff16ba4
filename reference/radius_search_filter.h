// The baseline hashed path space filtering approximates (Keller et al. 2016, "Path space filtering"): every filter
// vertex averages the contributions of all filter vertices within radius r of it that pass the same normal test,
// found with a k-d tree (nanoflann). At radius scale 1, r is HPSF's cell edge at the vertex's level: the accuracy
// HPSF buys back in time. Exact and deterministic: the tree only proposes candidates, each is held to the exact
// test of filter_vertices.h, and the contributions are summed in record order, so no bit depends on threads.
#ifndef HPSF_REFERENCE_RADIUS_SEARCH_FILTER_H
#define HPSF_REFERENCE_RADIUS_SEARCH_FILTER_H

#include "core/filter_config.h"
#include "core/record.h"
#include "reference/filter_vertices.h"

namespace hpsf {

NeighbourFilterResult RadiusSearchFilter(const RecordBatch& batch, const FilterConfig& config,
                                         double radius_scale = 1.0);

}  // namespace hpsf

#endif  // HPSF_REFERENCE_RADIUS_SEARCH_FILTER_H
