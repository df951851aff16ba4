// The contract's judgement of several filtered bounces (core/transport.h) on one frame of a hashed backend. Level 2:
// the checker transports the frame's records itself, from the backend's own table before the frame (which level 2
// judged a frame earlier), and holds the backend to it: every read is the slot that table holds the scattered
// vertex's cell in, or none, and the table checker then judges the table against the records so transported. Level 3:
// every read against the reference's in its exact map. A read is classified, not blamed, where the hashed table could
// not hold what the reference holds: the slot it read was classified, the lookup aliased (found a slot holding
// another cell), or it missed a cell that lost records to a probe failure or an eviction under pressure. A record
// whose read is classified carries other light into its own cells, which are then classified for the rest of the
// sequence (ClassifiedSlots::AddFrame's `fed`): an error in one frame's table is carried into every later frame.
#ifndef HPSF_VERIFIER_CONTRACT_TRANSPORT_CHECK_H
#define HPSF_VERIFIER_CONTRACT_TRANSPORT_CHECK_H

#include <cstdint>
#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/filter_result.h"
#include "core/hashed_run.h"
#include "verifier/checker/classified_slots.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf {

// Level 2: the batch as the frame should have added it to the run's table, its records and deeper ones transported
// from `before` where the configuration transports and there is a table before (the batch itself otherwise, without
// its scattered vertices); the run's reads judged against it.
RecordBatch JudgeTransportReads(const RecordBatch& batch, const FilterConfig& config, const HashTableDump* before,
                                const HashedRun& run, const std::string& prefix, LevelVerdict& tables);

struct TransportComparison {
  std::uint64_t compared = 0;    // reads equal to the reference's (a cell of the same key, or none on both sides)
  std::uint64_t classified = 0;  // reads classified
  std::vector<bool> fed;         // per record of records then deeper: its read was classified
};

// Level 3, before this frame's ClassifiedSlots::AddFrame: `classes` still describes the table before the frame.
TransportComparison CompareTransports(const RecordBatch& batch, const FilterConfig& config,
                                      const FilterResult& reference, const HashedRun& run,
                                      const ClassifiedSlots& classes, const std::string& prefix, LevelVerdict& ideal);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_TRANSPORT_CHECK_H
