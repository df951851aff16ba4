// The part of a filter run that the accumulate pass reads besides the key parameters: the table's shape and
// the fixed-point scale and the frame state, one block of 32-bit scalars shared by C++ and GLSL (after KeyParams
// in the accumulate shader's push constants).
#ifndef HPSF_CORE_SHARED_TABLE_PARAMS_H
#define HPSF_CORE_SHARED_TABLE_PARAMS_H

#include "prelude.h"
#include "probe_scheme.h"

HPSF_SHARED_BEGIN

const uint kAccumulateFixed64 = 0u;
const uint kAccumulateFloat32 = 1u;
const uint kAccumulatePackedDecimal = 2u;  // core/shared/packed_sums.h

// Placement of a record that holds no slot (core/hash_table.h names them for the host).
const uint kPlacementNotPlaced = 0xFFFFFFFFu;     // no vertex, unkeyable or rejected: never probed
const uint kPlacementProbeFailure = 0xFFFFFFFEu;  // probed its whole window without finding a slot

struct TableParams {
  uint capacity;            // a power of two
  uint probe_limit;         // the scheme's size: how many candidates a key has (core/shared/probe_scheme.h)
  float fixed_point_scale;  // 2^F for fixed64, 1000 for packed-decimal
  uint accumulation;        // kAccumulateFixed64, kAccumulateFloat32 or kAccumulatePackedDecimal
  // The frame state: with eviction, a slot a record is added to stores `frame` as its last-seen frame.
  uint frame;
  uint track_last_seen;  // 1 with eviction, else 0 (the last-seen buffer is then not written)
  // 1 when the frame blends (a blending --temporal and a table before it): bindings 9 and 10 then hold the table
  // before the frame and the push constants' TemporalParams its mode (table_interface.glsl). The blend is a pass
  // of its own after the accumulate; an accumulate reads none of it (docs/design/defects.md, D10).
  uint blending;
  // 1 with priority eviction: a slot tagged kTombstoneTag (core/shared/eviction_priority.h) may be claimed, so an
  // insertion first looks for its cell in the whole window up to the first empty slot, then claims the first empty
  // or tombstone slot (accumulate.glsl).
  uint claim_tombstones;
  uint probe_scheme;  // kProbeLinear, kProbeBucket or kProbeBucketWindow: the order of a key's candidates
  // Multi-level accumulation (core/shared/levels.h): a record is added at its own level and levels - 1 coarser ones,
  // its level k placement at placements[k n + i]; 1 adds it to its own cell only. Also keeps TemporalParams after it
  // 8-byte aligned.
  uint levels;
};

HPSF_FN ProbeScheme ProbeSchemeOf(TableParams t) { return MakeProbeScheme(t.probe_scheme, t.capacity, t.probe_limit); }

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_TABLE_PARAMS_H
