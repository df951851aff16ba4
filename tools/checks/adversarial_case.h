// Adversarial cases for `hpsf fuzz`: a table configuration, an emulator schedule and a small batch built to
// break a GPU hash table, each a pure function of (seed, run) through the counter RNG. Random batches almost never
// reach a table's hard cases, so each family constructs them (DESIGN.md, "Feed the oracle"): a crowded tiny table
// whose few cells repeat side by side (one subgroup races on one slot), keys whose fingerprint reduces to the
// empty tag, windows that wrap past the table's end, distinct keys that share slot0 and fingerprint, and the
// key path's boundary cases from the property-test generators; rejected, unkeyable and vertex-less records are
// mixed into every family. None is aimed at one defect: each is a kind of input a correct table must survive.
#ifndef HPSF_TOOLS_CHECKS_ADVERSARIAL_CASE_H
#define HPSF_TOOLS_CHECKS_ADVERSARIAL_CASE_H

#include <cstdint>
#include <optional>
#include <string>

#include "core/filter_config.h"
#include "core/record.h"
#include "emulated/emulated_filter.h"

namespace hpsf {

enum class AdversarialFamily { kCrowded, kZeroFingerprint, kWrappingWindows, kSharedFingerprint, kKeyPath };
inline constexpr int kAdversarialFamilies = 5;
const char* ToString(AdversarialFamily family);

struct AdversarialCase {
  AdversarialFamily family = AdversarialFamily::kCrowded;
  FilterConfig config;       // validated; frame 0, so `hpsf crosscheck` options express all of it
  EmulatorOptions emulator;  // faithful with a drawn warp size and schedule, or fast
  RecordBatch batch;         // width = records, height = 1, one sample per pixel
  std::string ToString() const;
};

struct AdversarialOptions {
  std::uint32_t max_records = 96;
  bool allow_fast_mode = true;  // false when a broken kernel runs: its races must replay from the schedule
  std::optional<Accumulation> accumulation;  // a user's shader may handle one mode only; else one in four is float32
};

AdversarialCase MakeAdversarialCase(std::uint32_t seed, std::uint64_t run, const AdversarialOptions& options = {});

}  // namespace hpsf

#endif  // HPSF_TOOLS_CHECKS_ADVERSARIAL_CASE_H
