// Level 3's judgement of the resolve's neighbourhood search (core/neighbour_search.h): for every record whose resolve
// searched, the cells its lookups found in the hashed table against those the reference found in its exact map,
// corner by corner. A record is classified, not blamed, where what it reads differs for a reason the contract
// classifies: a level of its own failed or sits in a classified slot, a corner's slot is classified, a lookup aliased
// (found a slot that holds another cell: a neighbour no record keyed shares a live cell's fingerprint in its window),
// or a neighbour the reference read was lost to a probe failure or an eviction under pressure. Any other difference
// is a failure: the search read a cell the reference did not, or missed one the reference read.
#ifndef HPSF_VERIFIER_CONTRACT_SEARCH_CHECK_H
#define HPSF_VERIFIER_CONTRACT_SEARCH_CHECK_H

#include <cstdint>
#include <string>
#include <vector>

#include "core/filter_result.h"
#include "core/hashed_run.h"
#include "verifier/checker/classified_slots.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf {

struct SearchComparison {
  std::uint64_t compared = 0;    // searching records whose every corner was judged
  std::uint64_t classified = 0;  // searching records classified (their image may differ from the reference's)
};

// classes: after AddFrame of this run; classified: what it returned.
SearchComparison CompareSearches(const RecordBatch& batch, const FilterResult& reference, const HashedRun& run,
                                 const ClassifiedSlots& classes, const std::vector<bool>& classified,
                                 const std::string& prefix, LevelVerdict& ideal);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_SEARCH_CHECK_H
