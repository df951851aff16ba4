// The cross-check contract (docs/design/contract.md) between backends on one batch or a sequence of frames through one
// table: level 1 keys (joins with Vulkan), level 2 every hashed backend passes the table checker (each frame from the
// table before it), level 3 agreement with the reference outside the records a backend classified (probe
// failures, aliased slots), level 4 determinism of a rerun. One module for `hpsf crosscheck`, `hpsf fuzz` and the
// tests; the levels themselves are verifier/contract/contract_levels.h.
#ifndef HPSF_VERIFIER_CONTRACT_CROSSCHECK_H
#define HPSF_VERIFIER_CONTRACT_CROSSCHECK_H

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/filter_config.h"
#include "core/hashed_run.h"
#include "core/record.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

struct LevelVerdict {
  int level = 0;
  std::string name;
  bool applicable = true;
  bool passed = true;
  std::string note;                   // why not applicable, or what was compared
  std::vector<std::string> failures;  // the first few, each naming records or slots
  static constexpr std::size_t kFailuresShown = 20;
  // Fails the level, keeping the first kFailuresShown failures.
  void Fail(std::string failure) {
    passed = false;
    if (failures.size() < kFailuresShown) failures.push_back(std::move(failure));
  }
};

// Summed over the frames of a sequence.
struct QualityFigures {
  std::string backend;
  std::uint64_t probe_failures = 0;
  std::uint64_t aliased_slots = 0;    // slots holding records of two or more full keys
  std::uint64_t aliased_records = 0;  // records placed in such slots (or holding a cell that failed before)
  // --neighbour-search: searching records classified (a level or a corner in a classified slot, a lookup that
  // aliased, a neighbour lost to a failure; verifier/contract/search_check.h)
  std::uint64_t classified_searches = 0;
  // Several filtered bounces: transport reads classified (verifier/contract/transport_check.h)
  std::uint64_t classified_transports = 0;
};

struct CrosscheckReport {
  std::vector<LevelVerdict> levels;
  std::vector<QualityFigures> quality;
  std::string vulkan_device;  // name and driver, when the Vulkan backend ran
  std::uint32_t frames = 1;
  // F, the fixed-point fraction bits every backend used (the reference's, chosen by the first frame or given by
  // --fixed-point-bits); in float32 the bits its range check assumed.
  int fixed_point_bits = 0;
  Accumulation accumulation = Accumulation::kFixed64;
  // With --second-moments: G, the square sums' fraction bits (core/shared/second_moment.h).
  std::optional<int> square_bits;
  bool Passed() const;
  // "level N NAME: " and the first failure of the first failed level (its note when it lists none); "" if passed.
  std::string FirstFailure() const;
  nlohmann::json ToJson() const;  // versioned
  std::string ToText() const;     // for people: each level's verdict and failures, then the figures
};

// Sees each frame a hashed backend filtered (not its rerun's), before it is judged: the records, the frame's number,
// the run and the table before it (null for a table that started empty). `hpsf crosscheck --capture` writes these.
using FrameObserver = std::function<void(const std::string& backend, const RecordBatch& batch, std::uint32_t frame,
                                         const HashedRun& run, const HashTableDump* before)>;

struct VulkanBackendOptions {
  std::string device_filter;   // --vk-device: a substring of the device name; empty picks the best
  std::string accumulate_spv;  // --accumulate-spv: a user's accumulate shader; empty for the built-in one
  std::string eviction_spv;    // --eviction-spv: a user's eviction shader; empty for the built-in one
  std::string temporal_spv;    // --temporal-spv: a user's temporal blend shader; empty for the built-in one
  std::string resolve_spv;     // --resolve-spv: a user's resolve shader; empty for the built-in ones
  std::string compaction_spv;  // --compaction-spv: a user's compaction shader; empty for the built-in one
  std::string transport_spv;   // --transport-spv: a user's transport shader; empty for the built-in one
  // --key-source shader: the accumulate shader's key words are its own (a team's quantization and hashes), judged
  // as given (verifier/contract/given_keys.h) instead of word for word against core's.
  bool shader_keys = false;
  StagingPolicy staging = StagingPolicy::kAuto;  // --vk-staging
};

// The cross-check of batch after batch (or sequence after sequence) on the same backends, keeping the Vulkan device
// and its pipelines from one to the next (hpsf fuzz judges thousands of small batches; creating a device costs
// more than one of them).
// backends: "reference", "emulated", "vulkan" (the reference is always run: it is the ideal).
// defect: a known broken kernel for the emulated backend, to show the gate fails.
class Crosschecker {
 public:
  Crosschecker(const std::vector<std::string>& backends, Defect defect = Defect::kNone,
               const VulkanBackendOptions& vulkan = {});
  ~Crosschecker();
  Crosschecker(const Crosschecker&) = delete;
  Crosschecker& operator=(const Crosschecker&) = delete;
  // One batch, filtered as frame config.frame.
  CrosscheckReport Check(const RecordBatch& batch, const FilterConfig& config, const EmulatorOptions& emulator);
  // A sequence through one table per backend, frame k filtered as frame frames[k].frame; config.frames should be
  // at least frames.size() (fixed64's F leaves room for that many).
  CrosscheckReport CheckFrames(std::span<const RecordBatch> frames, const FilterConfig& config,
                               const EmulatorOptions& emulator);
  void ObserveFrames(FrameObserver observer) { observer_ = std::move(observer); }

 private:
  CrosscheckReport Judge(std::span<const RecordBatch> frames, std::span<const std::uint32_t> numbers,
                         const FilterConfig& config, const EmulatorOptions& emulator);
  struct VulkanContext;
  std::vector<std::string> backends_;
  Defect defect_;
  VulkanBackendOptions vulkan_options_;
  FrameObserver observer_;
  std::unique_ptr<VulkanContext> vulkan_;  // created by the first batch that needs it
};

// One batch through a Crosschecker of its own.
CrosscheckReport Crosscheck(const RecordBatch& batch, const FilterConfig& config,
                            const std::vector<std::string>& backends, const EmulatorOptions& emulator,
                            Defect defect = Defect::kNone, const VulkanBackendOptions& vulkan = {});

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_CROSSCHECK_H
