// `hpsf judge`'s verdict on a capture (core/capture_file.h): one frame of a team's table, judged offline by the
// contract's levels (docs/design/contract.md#captures) with nothing of the team's engine but its buffers.
//   level 1  keys: every keyed record's home slot inside the table, its identity neither the empty marker nor wider
//            than the declared fingerprint, and records of equal key words given equal home slots and identities
//            (a key that is a function of the cell); with hpsf's records in the capture, every key word for word
//            against core's
//   level 2  the table checker from the table before the frame, as for a backend hpsf runs
//   level 3  agreement with the exact map over the captured key words: each cell's records in one slot (or all
//            failed), and outside the classified slots (aliases, failures) each slot's count, and in fixed64 its
//            sums, equal to its cell's exact ones, for a slot empty before the frame or integrating its history
//   level 4  with a rerun (a capture of the same frame from another run of the same inputs: `hpsf judge A --rerun
//            B`), what a rerun of an unordered run must repeat (verifier/contract/rerun_check.h): in fixed64 with
//            nothing failed or aliased in either, each record's count and sums; in float32 its count; else nothing.
//            Without one, not applicable: one capture is one run
// Bits the capture holds no image for are not judged (the host's "image is the resolve of its table").
#ifndef HPSF_VERIFIER_CONTRACT_CAPTURE_JUDGEMENT_H
#define HPSF_VERIFIER_CONTRACT_CAPTURE_JUDGEMENT_H

#include "core/capture_file.h"
#include "core/filter_config.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf {

// `config` is the capture's declaration applied to hpsf's defaults. A capture that contradicts it (capacity, sums
// encoding, last-seen frames with eviction) or that hpsf cannot judge is an InputError naming the capture; so is a
// rerun whose inputs (declaration, frame, records and their keys, table before) are not the capture's.
CrosscheckReport JudgeCapture(const Capture& capture, FilterConfig config, const Capture* rerun = nullptr);

// The captured keys as core's KeyResult: the key words in order (zero past key_words), the home slot as slot0, the
// identity as the fingerprint, the status as given, level 0.
std::vector<KeyResult> CapturedKeys(const Capture& capture);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_CAPTURE_JUDGEMENT_H
