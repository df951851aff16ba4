// The cross-check contract over a sequence of frames (one frame is a sequence of one), in code that needs no
// Vulkan: crosscheck.cpp adds the Vulkan backend through the same Backend interface, and the fuzz build
// (tools/fuzz, no Vulkan) judges the emulator with exactly this code. Per frame and hashed backend: level 1 its
// keys against core's (a backend that computes keys in its own code), level 2 the table checker from the table
// before the frame, level 3 agreement with the reference outside the classified slots (verifier/checker/
// classified_slots.h), level 4 a second instance of the backend over the same frames keeping its promise.
#ifndef HPSF_VERIFIER_CONTRACT_CONTRACT_LEVELS_H
#define HPSF_VERIFIER_CONTRACT_CONTRACT_LEVELS_H

#include <cstdint>
#include <span>
#include <string>

#include "core/backend.h"
#include "core/filter_config.h"
#include "core/record.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "emulated/emulated_filter.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf {

// A hashed backend the contract judges: two instances, the second for level 4's rerun.
struct JudgedBackend {
  std::string name;  // "emulated", "vulkan"
  Backend* backend = nullptr;
  Backend* rerun = nullptr;
  std::string rerun_how;    // what the rerun varies, for the note
  bool ordered = false;     // its order of memory operations is fixed (the faithful emulator): reruns repeat it
  bool judge_keys = false;  // level 1: its keys come from its own code (the Vulkan shaders)
  // Its keys are a team's own (--key-source shader): level 1 judges them as given, level 3 against the exact map
  // over their key words instead of hpsf's reference (verifier/contract/given_keys.h).
  bool shader_keys = false;
};

// The emulated backend and its rerun: in fast mode on another number of worker threads, since no promised bit may
// depend on it; `defect` names a known broken kernel, to show the contract fails.
class EmulatedPair {
 public:
  EmulatedPair(const EmulatorOptions& emulator, Defect defect);
  JudgedBackend Judged();

 private:
  static EmulatorOptions RerunOptions(const EmulatorOptions& emulator);
  EmulatorOptions options_;
  EmulatedBackend backend_, rerun_;
};

// frames[k] filtered as frame numbers[k] through one table per backend (each Reset first), the reference always:
// the four levels of every frame, each failure naming its frame when there are several.
CrosscheckReport JudgeSequence(std::span<const RecordBatch> frames, std::span<const std::uint32_t> numbers,
                               FilterConfig config, std::span<const JudgedBackend> hashed,
                               const FrameObserver& observer = {});

// The reference and the emulated backend on one batch, as frame config.frame: Crosscheck(batch, config,
// {"reference", "emulated"}, ...) without linking Vulkan.
CrosscheckReport CrosscheckEmulated(const RecordBatch& batch, const FilterConfig& config,
                                    const EmulatorOptions& emulator, Defect defect = Defect::kNone);

// The same over a sequence: each frame judged as its own batch's frame number.
CrosscheckReport CrosscheckEmulatedSequence(std::span<const RecordBatch> frames, const FilterConfig& config,
                                            const EmulatorOptions& emulator);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_CONTRACT_LEVELS_H
