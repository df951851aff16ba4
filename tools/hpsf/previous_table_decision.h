// Where a traced sequence's adaptive decisions come from (survival, core/survival.h; path graphs, core/path_graph.h):
// the view of the table before the frame that the tracer reads for a frame, or none where the effect plan skips the
// read (a sequence's first frame, unless forced, where every path survives and none is cut).
#ifndef HPSF_TOOLS_HPSF_PREVIOUS_TABLE_DECISION_H
#define HPSF_TOOLS_HPSF_PREVIOUS_TABLE_DECISION_H

#include <cstdint>
#include <optional>

#include "core/filter_config.h"
#include "core/filter_result.h"
#include "core/hash_table.h"
#include "core/previous_table_view.h"
#include "tracer/path_tracer.h"

namespace hpsf {

// The view for the frame at place `index` of its sequence (config.frame its number) traced with `trace` in
// `prepared`: from the reference's exact map `exact` or a hashed backend's `hashed` (one of them, the frame before's;
// both null on the first frame). The table must outlive the view.
std::optional<PreviousTableView> FramePreviousTableView(const FilterConfig& config, const TraceOptions& trace,
                                                        const PreparedScene& prepared, std::uint32_t index,
                                                        const FilterResult* exact, const HashTableDump* hashed);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_PREVIOUS_TABLE_DECISION_H
