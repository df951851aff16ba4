// fuzz_read_back: the host against whatever a shader might leave in its buffers. The input decodes (fuzz_batch.h)
// into a small table and a batch (packed-decimal sums among them), then a sequence of 1 to 4 frames with an eviction
// policy (none, strict, stale:N, priority), a temporal mode (integrate, ema, adaptive) and a level change (reset or
// seed), which the faithful emulator filters, carrying its table. Each frame's run is then corrupted as a broken or
// hostile shader would leave it: words of one binding (keys, placements, tags, sums, counts, last-seen frames, the
// stats words, the resolved pixels) overwritten with the input's bytes, a few at chosen places or all of them. The
// corrupted runs go through the host's read-back (core/read_back_check.h: FinishReadBack) and the whole contract,
// exactly as `hpsf crosscheck` judges a Vulkan run (verifier/contract/contract_levels.h). A bug: a crash, a sanitizer
// report, a hang or an exception escaping the contract. Any verdict is accepted. Built twice: as a libFuzzer target
// (preset fuzz) and as the ctest read_back_fuzz_tests, which runs the checked-in corpus and a fixed number of inputs
// from the counter RNG (untrusted_inputs_main.cpp).
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "core/error.h"
#include "core/read_back_check.h"
#include "emulated/emulated_backend.h"
#include "tools/fuzz/fuzz_batch.h"
#include "verifier/contract/contract_levels.h"

namespace hpsf {
namespace {

// kStats: the counters read back beside the table (the stats words, the evicted and seeded counts).
// kFrameCounters: packed-decimal's, split from its count words (empty otherwise).
enum class Binding {
  kKeys,
  kPlacements,
  kTags,
  kSums,
  kCounts,
  kLastSeen,
  kStats,
  kPixels,
  kFrameCounters,
  kMaxValue = kFrameCounters
};

std::array<std::uint64_t, 4> Counters(const HashedRun& run) {
  return {run.wraps, run.count_wraps, run.evicted, run.seeded};
}

// Words of one binding, as bytes the input overwrites (kStats has no array of its own: Corrupt copies it).
std::span<std::uint8_t> BindingBytes(HashedRun& run, Binding binding) {
  HashTableDump& t = run.table;
  auto bytes = [](auto& vector) {
    return std::span<std::uint8_t>(reinterpret_cast<std::uint8_t*>(vector.data()), vector.size() * sizeof(vector[0]));
  };
  switch (binding) {
    case Binding::kKeys:
      return bytes(run.keys);
    case Binding::kPlacements:
      return bytes(run.placements);
    case Binding::kTags:
      return bytes(t.tags);
    case Binding::kSums:
      return IntegerSums(t.accumulation) ? bytes(t.fixed_sums) : bytes(t.float_sums);
    case Binding::kCounts:
      return bytes(t.counts);
    case Binding::kLastSeen:
      return bytes(t.last_seen);
    case Binding::kStats:
      return {};
    case Binding::kPixels:
      return bytes(run.image.pixels);
    case Binding::kFrameCounters:
      return bytes(t.frame_counters);
  }
  return {};
}

// Overwrites 4-byte words: a few at places the input picks, or every word from the input's bytes.
void OverwriteWords(FuzzedDataProvider& input, std::span<std::uint8_t> bytes) {
  const std::size_t words = bytes.size() / 4;
  if (words == 0) return;
  if (input.ConsumeBool()) {
    for (int n = input.ConsumeIntegralInRange<int>(1, 4); n > 0; --n) {
      const std::size_t w = input.ConsumeIntegralInRange<std::size_t>(0, words - 1);
      const std::uint32_t value = input.ConsumeIntegral<std::uint32_t>();
      std::memcpy(bytes.data() + 4 * w, &value, 4);
    }
  } else {
    const std::vector<std::uint8_t> fill = input.ConsumeBytes<std::uint8_t>(64);
    if (fill.empty()) return;
    for (std::size_t b = 0; b < bytes.size(); ++b) bytes[b] = fill[b % fill.size()];
  }
}

// Overwrites words of one binding of the run.
void Corrupt(FuzzedDataProvider& input, HashedRun& run) {
  const Binding binding = input.ConsumeEnum<Binding>();
  if (binding != Binding::kStats) {
    OverwriteWords(input, BindingBytes(run, binding));
    return;
  }
  std::array<std::uint64_t, 4> counters = Counters(run);
  OverwriteWords(input, std::span<std::uint8_t>(reinterpret_cast<std::uint8_t*>(counters.data()), sizeof counters));
  run.wraps = counters[0];
  run.count_wraps = counters[1];
  run.evicted = counters[2];
  run.seeded = counters[3];
}

bool Differ(HashedRun& a, HashedRun& b) {
  if (Counters(a) != Counters(b)) return true;
  for (int binding = 0; binding <= int(Binding::kMaxValue); ++binding) {
    const std::span<const std::uint8_t> x = BindingBytes(a, Binding(binding)), y = BindingBytes(b, Binding(binding));
    if (!std::equal(x.begin(), x.end(), y.begin(), y.end())) return true;
  }
  return false;
}

// A hashed backend whose frames are runs captured beforehand: each goes through the host's read-back as a Vulkan
// run does.
class CapturedBackend : public Backend {
 public:
  explicit CapturedBackend(const std::vector<HashedRun>& frames) : frames_(frames) {}
  std::string Name() const override { return "captured"; }
  const HashedRun* LastHashedRun() const override { return run_ ? &*run_ : nullptr; }

 protected:
  const Image& FilterFrameInto(const RecordBatch&, const FilterConfig& config, std::uint32_t index) override {
    run_.reset();
    HashedRun run = frames_.at(index);
    FinishReadBack(run, config.frame, "the fuzzed buffers");
    run_ = std::move(run);
    return run_->image;
  }
  void ForgetTable() override { run_.reset(); }

 private:
  const std::vector<HashedRun>& frames_;
  std::optional<HashedRun> run_;
};

constexpr const char* kEvictions[] = {"none", "strict", "stale:1", "stale:2", "priority"};
constexpr const char* kTemporals[] = {"integrate", "ema:0.5", "ema:0.25:4", "adaptive"};
constexpr const char* kLevelChanges[] = {"none", "seed:0", "seed:1"};

template <std::size_t N>
const char* Pick(FuzzedDataProvider& input, const char* const (&names)[N]) {
  return names[input.ConsumeIntegralInRange<std::size_t>(0, N - 1)];
}

}  // namespace
}  // namespace hpsf

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hpsf;
  FuzzedDataProvider input(data, size);
  FuzzCase c = DecodeFuzzCase(input, true);
  const std::uint32_t frames = input.ConsumeIntegralInRange<std::uint32_t>(1, 4);
  try {
    c.config.eviction = ParseEviction(Pick(input, kEvictions));
    c.config.temporal = ParseTemporal(Pick(input, kTemporals));
    c.config.level_seed = ParseLevelSeed(Pick(input, kLevelChanges));
    if (c.config.level_seed.enabled) c.config.lod = true;  // seeding needs levels of detail
    c.config.frames = frames;
    if (c.config.eviction.by_priority()) c.config.fingerprint_bits = std::min(c.config.fingerprint_bits, 31u);
    c.config.Validate();
  } catch (const ConfigError&) {
    return 0;  // a combination the command line refuses too
  }
  // The correct runs, frame by frame through one table, then each corrupted.
  std::vector<std::uint32_t> numbers(frames);
  std::vector<HashedRun> runs;
  EmulatedBackend emulated(c.faithful);
  for (std::uint32_t k = 0; k < frames; ++k) {
    numbers[k] = k;
    FilterConfig config = c.config;
    config.frame = k;
    emulated.FilterFrame(c.batch, config);
    runs.push_back(*emulated.LastHashedRun());
  }
  std::vector<HashedRun> correct = runs;
  bool corrupted = false;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    for (int n = input.ConsumeIntegralInRange<int>(0, 2); n > 0; --n) Corrupt(input, runs[k]);
    corrupted = corrupted || Differ(runs[k], correct[k]);
  }
  CapturedBackend captured(runs), rerun(runs);
  const JudgedBackend judged{"captured", &captured, &rerun, "the same buffers", true, true};
  const std::vector<RecordBatch> batches(frames, c.batch);
  const CrosscheckReport report = JudgeSequence(batches, numbers, c.config, std::span<const JudgedBackend>(&judged, 1));
  // The oracle's other side: the emulator's own runs, uncorrupted, pass through the read-back and the contract, unless
  // packed-decimal words passed their range, which the contract names (fuzz_batch.h).
  if (!corrupted && !report.Passed() && !BeyondPackedDecimal(c.config, report)) {
    std::fprintf(stderr, "fuzz_read_back: uncorrupted runs fail the contract: %s\n%s", report.FirstFailure().c_str(),
                 c.ToString().c_str());
    std::abort();
  }
  return 0;
}
