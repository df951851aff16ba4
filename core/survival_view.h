// The table a frame's survival decisions read (core/survival.h): the one the frame before left, from the reference's
// exact map or a hashed backend's own table, looked up by the key of a sample's primary vertex.
#ifndef HPSF_CORE_SURVIVAL_VIEW_H
#define HPSF_CORE_SURVIVAL_VIEW_H

#include <functional>
#include <optional>

#include "core/accumulation.h"
#include "core/key_batch.h"
#include "core/record.h"
#include "core/survival.h"
#include "core/temporal.h"

namespace hpsf {

struct FilterResult;   // core/filter_result.h
struct HashTableDump;  // core/hash_table.h

// The previous table must outlive the view.
class SurvivalView {
 public:
  // No table before the frame (a sequence's first, where survival is forced): every path survives, p = 1.
  SurvivalView(const SurvivalParams& params, const KeyParams& key_params);
  // The reference's exact map.
  SurvivalView(const SurvivalParams& params, const KeyParams& key_params, const FilterResult& previous,
               Accumulation accumulation);
  // A hashed backend's table (its second moments kept), looked up as the level seed looks a cell up.
  SurvivalView(const SurvivalParams& params, const KeyParams& key_params, const HashTableDump& previous,
               bool normal_in_index);

  const SurvivalParams& params() const { return params_; }
  // The probability that the sample whose primary vertex is `vertex` (a record with a vertex, its contribution not
  // read) is traced on: p of its cell's variance, or 1 where the table says nothing of it.
  double Probability(const Record& vertex) const;

 private:
  SurvivalParams params_;
  KeyParams key_params_;
  Accumulation accumulation_;
  int fixed_point_bits_ = 0;
  int square_bits_ = 0;
  std::function<std::optional<CellState>(const shared::KeyWords&)> lookup_;
};

}  // namespace hpsf

#endif  // HPSF_CORE_SURVIVAL_VIEW_H
