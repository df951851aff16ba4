// The cross-check contract's levels 2 to 4 for one hashed run, and the whole contract between the reference and
// the emulated backend, in code that needs no Vulkan: crosscheck.cpp adds level 1 and the Vulkan backend with the
// same pieces, and the fuzz build (tools/fuzz, no Vulkan) judges the emulator with exactly this code.
#ifndef HPSF_TOOLS_CHECKS_CONTRACT_LEVELS_H
#define HPSF_TOOLS_CHECKS_CONTRACT_LEVELS_H

#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/filter_result.h"
#include "core/hashed_run.h"
#include "core/record.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "tools/checks/crosscheck.h"

namespace hpsf {

// The four levels of one cross-check, filled in by the backends' judges.
struct ContractVerdicts {
  LevelVerdict keys, tables, ideal, determinism;
  explicit ContractVerdicts(bool hashed);
  std::vector<LevelVerdict> Levels() const { return {keys, tables, ideal, determinism}; }
};

void Fail(LevelVerdict& verdict, std::string failure);  // keeps the first few failures
void Note(LevelVerdict& verdict, const std::string& backend, const std::string& text);

// Level 2: the table checker on one hashed run.
void CheckTableOf(const std::string& backend, const RecordBatch& batch, const HashedRun& run, LevelVerdict& tables);
// Level 2 and the run's quality figures (appended to the report); returns which slots aliased.
std::vector<bool> JudgeTable(const std::string& backend, const RecordBatch& batch, const HashedRun& run, CrosscheckReport& report,
                             LevelVerdict& tables);
// Level 3 for one hashed run against the reference; returns what was compared, for the verdict's note.
std::string CompareWithReference(const RecordBatch& batch, const FilterConfig& config, const FilterResult& reference, const HashedRun& run,
                                 const std::vector<bool>& aliased, const std::string& prefix, LevelVerdict& ideal);
// Level 4: a rerun keeps what the contract promises for its kind of run.
void JudgeRerun(const std::string& backend, const HashedRun& first, const HashedRun& second, bool ordered,
                const QualityFigures& quality, const std::string& how, LevelVerdict& determinism);
// Levels 2 to 4 for the emulated backend (with a broken kernel when `defect` names one).
void JudgeEmulated(const RecordBatch& batch, const FilterConfig& config, const FilterResult& reference, const EmulatorOptions& emulator,
                   Defect defect, CrosscheckReport& report, ContractVerdicts& verdicts);

// The reference and the emulated backend on one batch: Crosscheck(batch, config, {"reference", "emulated"}, ...)
// without linking Vulkan.
CrosscheckReport CrosscheckEmulated(const RecordBatch& batch, const FilterConfig& config, const EmulatorOptions& emulator,
                                    Defect defect = Defect::kNone);

}  // namespace hpsf

#endif  // HPSF_TOOLS_CHECKS_CONTRACT_LEVELS_H
