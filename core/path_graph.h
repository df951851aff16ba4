// Adaptive path graphs (Schipek §4.2, eq. 4.7, Algorithm 2): a path keeps a running estimate of the variance it has
// gathered, each vertex adding tp^2 V, the squared throughput from the filter vertex to it times the variance of its
// cell in the table the frame before left (the variance of what the rest of the path would add there). Where the sum
// would pass the bound, the path is cut: the cell's average, which has no variance this frame, takes weight 1 - alpha
// and the path traced on takes alpha = sqrt((bound - variance) / local), so that the sum reaches the bound exactly
// (eq. 4.15). A path never cut is path tracing; a bound of 0 cuts every path at its filter vertex's cell (HPSF).
//
// Departure from Algorithm 2 as printed: it weighs only the cut vertex's next-event estimate by alpha and drops the
// path after it, which loses alpha times the indirect light (dark in a furnace). hpsf weighs the whole rest of the
// path by alpha, so a pixel's expected light is (1 - alpha) the cell's plus alpha the path's: unbiased wherever the
// cell is. The decision reads the table before the frame only, through PreviousTableView (core/previous_table_view.h),
// as survival does: every backend is handed the same records.
#ifndef HPSF_CORE_PATH_GRAPH_H
#define HPSF_CORE_PATH_GRAPH_H

#include <string>

namespace hpsf {

struct PathGraphParams {
  bool enabled = false;
  double bound = 0.0;  // the variance constant of eq. 4.7, finite and >= 0
  // false only in tests: the broken variant "a path graph that cuts after the bound is exceeded", which traces the
  // vertex that passes the bound in full and cuts at the next cell.
  bool cut_before_exceeding = true;
  std::string ToString() const;  // "off" or the bound
  bool operator==(const PathGraphParams&) const = default;
};

// "off" or a bound, a finite number >= 0; a ConfigError naming --path-graph otherwise.
PathGraphParams ParsePathGraph(const std::string& text);

// One vertex's step along a path that has gathered `variance` (<= the bound) and is not cut yet, at a cell whose
// variance times the squared throughput is `local` (>= 0).
struct PathGraphStep {
  bool cut = false;
  double alpha = 1.0;     // the weight of the path traced on from this vertex; 1 - alpha is the cell's
  double variance = 0.0;  // the path's variance after the vertex: the bound where cut
};
PathGraphStep StepPathGraph(const PathGraphParams& params, double variance, double local);

}  // namespace hpsf

#endif  // HPSF_CORE_PATH_GRAPH_H
