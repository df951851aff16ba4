// A frame of one of hpsf's own hashed runs written as a capture, through the same header a team's engine calls
// (core/capture_writer.h): `hpsf crosscheck --capture DIR` writes these, and `hpsf judge` must then give the verdict
// the host gave.
#ifndef HPSF_VERIFIER_CONTRACT_RUN_CAPTURE_H
#define HPSF_VERIFIER_CONTRACT_RUN_CAPTURE_H

#include <string>

#include "core/hashed_run.h"
#include "core/record.h"

namespace hpsf {

// `declaration` is the run's table declaration (verifier/gate/table_declaration.h, TableDeclarationText); `before`
// the table before the frame, or null when it started empty. The keys are hpsf's (six words), and the records go
// with them, so that the judge compares them with core's. Throws InputError when the file cannot be written.
void WriteRunCapture(const std::string& path, const std::string& declaration, const RecordBatch& batch,
                     std::uint32_t frame, const HashedRun& run, const HashTableDump* before);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_RUN_CAPTURE_H
