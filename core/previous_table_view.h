// The table a traced frame's adaptive decisions read: path survival (core/survival.h) and the cuts of path graphs
// (core/path_graph.h). It is the one the frame before left, from the reference's exact map or a hashed backend's own
// table, looked up by the key of a path's vertex.
#ifndef HPSF_CORE_PREVIOUS_TABLE_VIEW_H
#define HPSF_CORE_PREVIOUS_TABLE_VIEW_H

#include <functional>
#include <optional>

#include <glm/vec3.hpp>

#include "core/accumulation.h"
#include "core/cell_moments.h"
#include "core/filter_config.h"
#include "core/key_batch.h"
#include "core/path_graph.h"
#include "core/record.h"
#include "core/survival.h"
#include "core/temporal.h"

namespace hpsf {

struct FilterResult;   // core/filter_result.h
struct HashTableDump;  // core/hash_table.h

// What the view knows of a vertex's cell: its average (sums / count, as the resolve of one cell reads it) and its
// moments, from two samples on.
struct CellEstimate {
  glm::dvec3 average{0.0};
  CellMoments moments;
};

// The previous table must outlive the view.
class PreviousTableView {
 public:
  // No table before the frame (a sequence's first, where the effects are forced): every path survives, none is cut.
  PreviousTableView(const FilterConfig& config, const KeyParams& key_params);
  // The reference's exact map.
  PreviousTableView(const FilterConfig& config, const KeyParams& key_params, const FilterResult& previous);
  // A hashed backend's table (its second moments kept), looked up as the level seed looks a cell up.
  PreviousTableView(const FilterConfig& config, const KeyParams& key_params, const HashTableDump& previous);

  const SurvivalParams& survival() const { return survival_; }
  const PathGraphParams& path_graph() const { return path_graph_; }
  // The probability that the sample whose primary vertex is `vertex` (a record with a vertex, its contribution not
  // read) is traced on: p of its cell's variance, or 1 where the table says nothing of it (or survival is off).
  double Probability(const Record& vertex) const;
  // The cell of `vertex` (a record with a vertex, keyed at its own bounce), where it holds two samples or more.
  std::optional<CellEstimate> Cell(const Record& vertex) const;

 private:
  SurvivalParams survival_;
  PathGraphParams path_graph_;
  KeyParams key_params_;
  Accumulation accumulation_;
  int fixed_point_bits_ = 0;
  int square_bits_ = 0;
  std::function<std::optional<CellState>(const shared::KeyWords&)> lookup_;
};

}  // namespace hpsf

#endif  // HPSF_CORE_PREVIOUS_TABLE_VIEW_H
