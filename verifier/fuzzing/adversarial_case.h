// Adversarial cases for `hpsf fuzz`: a table configuration, an emulator schedule and a small batch built to
// break a GPU hash table, each a pure function of (seed, run) through the counter RNG. Random batches almost never
// reach a table's hard cases, so each family constructs them (docs/design/testing.md, "Feed the oracle"): a crowded
// tiny table whose few cells repeat side by side (one subgroup races on one slot), keys whose fingerprint reduces to
// the empty tag, windows that wrap past the table's end, distinct keys that share slot0 and fingerprint, and the key
// path's boundary cases from the property-test generators; rejected, unkeyable and vertex-less records are mixed into
// every family. None is aimed at one defect: each is a kind of input a correct table must survive. Three dimensions cut
// across the families, each for a class of bug that the plain cases hide: the spread family (Vulkan only) lays a few
// cells over several of the Vulkan accumulate's workgroups at matching offsets, since lavapipe runs a workgroup's
// subgroups one after another and only its worker threads truly interleave (a race one execution order hides); one
// fixed64 case in four takes a small F of its own, from -2 to 9 bits, where c * 2^F has a fraction and rounding matters
// (the automatic F makes it whole and hides truncation); and one case in four is a sequence of 2 to 6 frames through
// one table, with a drawn eviction policy and temporal mode, whose later frames revisit the first frame's records and
// add new ones (a frame-state defect one frame hides); half the sequences keep an occupied list (core/compaction.h),
// and a later frame in eight sees only sky, so that a policy may evict every cell. Half the sequences not in
// packed-decimal transport light between frames (several filtered bounces): each record scatters to the vertex of
// another record of its frame, so a later frame finds the cells the frame before filled.
#ifndef HPSF_VERIFIER_FUZZING_ADVERSARIAL_CASE_H
#define HPSF_VERIFIER_FUZZING_ADVERSARIAL_CASE_H

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/record.h"
#include "emulated/emulated_filter.h"

namespace hpsf {

enum class AdversarialFamily { kCrowded, kZeroFingerprint, kWrappingWindows, kSharedFingerprint, kKeyPath, kSpread };
inline constexpr int kAdversarialFamilies = 6;

// The Vulkan accumulate's records per workgroup (local_size_x 128, 16 records per invocation: vulkan_filter.cpp).
inline constexpr std::uint32_t kAccumulateRecordsPerWorkgroup = 2048;
const char* ToString(AdversarialFamily family);

struct AdversarialCase {
  AdversarialFamily family = AdversarialFamily::kCrowded;
  FilterConfig config;             // validated; frame 0, so `hpsf crosscheck` options express all of it
  EmulatorOptions emulator;        // faithful with a drawn warp size and schedule, or fast
  RecordBatch batch;               // the first frame: width = records, height = 1, one sample per pixel, frame 0
  std::vector<RecordBatch> later;  // a sequence's frames after the first, numbered 1, 2, ... (may skip once shrunk)
  std::vector<RecordBatch> Frames() const;  // batch, then later
  std::size_t Records() const;              // over every frame
  std::string ToString() const;
};

struct AdversarialOptions {
  std::uint32_t max_records = 96;  // per frame; the spread family sizes its batches by workgroups instead
  bool allow_fast_mode = true;     // false when a broken kernel runs: its races must replay from the schedule
  // A user's shader may handle one mode only; else one in four is float32, and one in six packed-decimal.
  std::optional<Accumulation> accumulation;
  // The spread family's thousands of records are for a device whose workgroups run at once (Vulkan); the emulator
  // interleaves a race by its schedule in a few records, and skips the family.
  bool spread = true;
  // The probing scheme of every case; unset, each case draws one (half linear, a quarter each bucket and
  // bucket-window), its size from the family (a bucket's rounded down to a power of two).
  std::optional<ProbeKind> probing = std::nullopt;
  // Whether a case may store full keys (core/key_identity.h): false where a team's shader reads 32-bit tags only.
  bool full_keys = true;
  // Whether a case may store fingerprints: false where a team's shader reads 64-bit tags only; every case then
  // stores full keys, its normal bucket narrowed to one that fits.
  bool fingerprints = true;
  // Whether a case may draw packed-decimal sums: false where a team's eviction shader reads 64-bit counts only.
  bool packed_sums = true;
  // Whether a case may add records at several levels (--levels): false where a broken kernel or a team's accumulate
  // or resolve shader runs, which need not know them.
  bool levels = true;
  // Whether a case may search the neighbours of cells below the threshold (--neighbour-search): false where a team's
  // accumulate or resolve shader runs.
  bool search = true;
  // Whether a sequence with level of detail may seed the cells new at another level (--level-change seed): false
  // where a broken kernel or a team's shader runs, which need not keep a table level seeding can read.
  bool level_change = true;
  // Whether a sequence may transport its scattered vertices' light (--transport, core/transport.h): false on Vulkan
  // where a broken kernel or a team's shader runs, so that what the fuzzer finds there stays the shader's.
  bool transport = true;
  // Whether a case may keep second moments (--second-moments, core/shared/second_moment.h): false where a broken
  // kernel or a team's accumulate, temporal or eviction shader runs, which need not keep the squares.
  bool second_moments = true;
  // Whether a case that keeps second moments may interpolate (--interpolation, core/cell_interpolation.h): false where
  // a team's resolve shader runs, whose interface has no interpolation.
  bool interpolation = true;
};

AdversarialCase MakeAdversarialCase(std::uint32_t seed, std::uint64_t run, const AdversarialOptions& options = {});

}  // namespace hpsf

#endif  // HPSF_VERIFIER_FUZZING_ADVERSARIAL_CASE_H
