// Broken variants of several filtered bounces' transport (core/transport.h; docs/design/defects.md, "Broken
// transport"), for the emulator's transport pass: each a way a team's nHPSF goes wrong, which the contract must catch
// over a sequence of frames (the first frame transports nothing, so none of them is a Defect value).
#ifndef HPSF_EMULATED_BROKEN_TRANSPORT_H
#define HPSF_EMULATED_BROKEN_TRANSPORT_H

#include <cstdint>
#include <span>
#include <string>

#include "core/key_batch.h"
#include "core/record.h"
#include "core/transport.h"

namespace hpsf {

enum class TransportDefect {
  kNone,
  // The transport weight applied twice: the scattered vertex's throughput multiplied in once more.
  kWeightTwice,
  // The scattered vertex's cell keyed at the level of the vertex it scattered from (under level of detail, the
  // primary's path length chooses the cell size): a lookup of the wrong cell size.
  kScatteredAtRecordLevel,
  // The lookup reads the table being accumulated, not the one before the frame (D10's cousin): each record looks up
  // its scattered vertex's cell inside the accumulate's launch (TransportDuringAccumulate,
  // emulated/defect_injection.h), so it sees whichever of the frame's adds came first, and cells new in the frame: a
  // race the schedules explore.
  kReadsCurrentTable,
};

// What kReadsCurrentTable's accumulate reads besides its own arguments, per record of records then deeper.
struct TransportInPassArgs {
  // The scattered vertex's key (shared::ComputeKey), or a kKeyNoVertex key where the record transports nothing
  // (it or its scattered vertex has no vertex or failed the input checks).
  std::span<const KeyResult> scattered_keys;
  std::span<const Record> scattered;  // their throughputs carry the light back
  int fixed_point_bits = 0;           // the table's F
  std::uint32_t reads = 0;            // 32-bit buffer: the slot each record read, or kNothingTransported
};

// "none", "weight-twice", "scattered-at-record-level", "reads-current-table"
std::string ToString(TransportDefect defect);

// The batch whose correct transport is the weight-twice one: each scattered vertex's throughput squared. The batch
// itself otherwise.
RecordBatch WithWeightTwice(const RecordBatch& batch);

// kScatteredAtRecordLevel's key: the scattered vertex's jittered position, quantised at the record's level.
KeyResult KeyAtRecordLevel(const KeyParams& params, const Record& scattered, const Record& record);

}  // namespace hpsf

#endif  // HPSF_EMULATED_BROKEN_TRANSPORT_H
