// Level 3's judgement of a hashed backend's image: it must be the resolve (core/resolve) of the backend's own
// table, every record taking the average of the slot it was placed in. fixed64 sums are exact, so the image is
// bit-identical to core's resolve of them. float32 sums are rounded in whatever order the atomics applied, so
// the image is held to the exact resolve (each slot's sum taken exactly from the records placed there) within
// what the per-slot bound of docs/design/contract.md, gamma(n - 1) * sum|c|, allows after the throughput and the pixel
// mean, plus the final rounding to float. Where nothing failed or aliased, the records of a slot are exactly those of
// the reference's cell (level 3 checks that apart), so this is the bound against the exact reference. Over frames, a
// float32 slot that held samples before the frame carries a sum rounded in earlier frames (and blended): the table
// checker bounds it (level 2), and the image is held to the resolve of the table's own sum. So is a record whose
// resolve searched its neighbours (core/neighbour_search.h): it reads the slots a lookup finds in the table read back.
#ifndef HPSF_VERIFIER_CONTRACT_IMAGE_CHECK_H
#define HPSF_VERIFIER_CONTRACT_IMAGE_CHECK_H

#include <string>
#include <vector>

#include "core/hashed_run.h"
#include "core/record.h"

namespace hpsf {

// Pixels outside what the table allows, each named with its channel, value, expected value and bound; empty
// when the image holds. The run's table must have passed the table checker. before: the table before the frame,
// null for a frame that started from an empty one.
std::vector<std::string> CheckImageAgainstTable(const RecordBatch& batch, const HashedRun& run,
                                                const HashTableDump* before = nullptr);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_IMAGE_CHECK_H
