// The families a gate file declares (verifier/gate/gate_file.h), each expanded into cases that are command lines of
// the hpsf command the family runs:
//
//   crosscheck  scene x config x backend x sequence x seed   `hpsf crosscheck`: every level of the contract
//   statistics  scene x config x seed                         `hpsf stats`: load, probes, aliases, jitter against
//                                                             their theory (a rate above it warns)
//   golden      one case per golden of a manifest             `hpsf golden check`: the image against its golden
//   fuzz        backend x seed, a budget of runs              `hpsf fuzz`: adversarial batches, shrunk on failure
//   captures    one case per capture or folder of them         `hpsf judge`: a team's frames, captured in its engine
//
// Cases are appended in that order of families, each family's coordinates sorted as the file's objects are, so a
// gate's case list (and so its shards) is a function of the file alone.
#ifndef HPSF_VERIFIER_GATE_GATE_FAMILIES_H
#define HPSF_VERIFIER_GATE_GATE_FAMILIES_H

#include <string>

#include <nlohmann/json.hpp>

#include "verifier/gate/gate_expansion.h"
#include "verifier/gate/gate_file.h"

namespace hpsf::gate {

// Each reads document[family] (family's pointer "/" + name) and appends its cases to `gate`; `folder` resolves
// the file's relative paths.
void ExpandCrosscheck(const nlohmann::json& family, const std::string& folder, const GateError& error, Gate& gate);
void ExpandStatistics(const nlohmann::json& family, const std::string& folder, const GateError& error, Gate& gate);
void ExpandGolden(const nlohmann::json& family, const std::string& folder, const GateError& error, Gate& gate);
void ExpandFuzz(const nlohmann::json& family, const std::string& folder, const GateError& error, Gate& gate);
void ExpandCaptures(const nlohmann::json& family, const std::string& folder, const GateError& error, Gate& gate);

}  // namespace hpsf::gate

#endif  // HPSF_VERIFIER_GATE_GATE_FAMILIES_H
