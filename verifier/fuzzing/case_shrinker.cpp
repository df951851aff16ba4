#include "verifier/fuzzing/case_shrinker.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "core/error.h"

namespace hpsf {
namespace {

class Shrinker {
 public:
  Shrinker(const CaseFailsFn& fails, ShrinkKeeps keep, std::uint64_t max_checks)
      : fails_(fails), keep_(keep), max_checks_(max_checks) {}

  bool Fails(const AdversarialCase& candidate) {
    if (checks_ >= max_checks_) {
      exhausted_ = true;
      return false;
    }
    ++checks_;
    return fails_(candidate);
  }

  // A sequence's frames: each later one dropped, last first, then the first (a later frame takes its place), while
  // the case still fails. Frame numbers are kept: what a frame-state defect needs is their distance.
  void ShrinkFrames(AdversarialCase& c) {
    for (std::size_t k = c.later.size(); k > 0 && !exhausted_; --k) {
      AdversarialCase candidate = c;
      candidate.later.erase(candidate.later.begin() + std::ptrdiff_t(k - 1));
      candidate.config.frames = std::uint32_t(candidate.later.size() + 1);
      if (Fails(candidate)) c = std::move(candidate);
    }
    if (!c.later.empty() && !exhausted_) {
      AdversarialCase candidate = c;
      candidate.batch = candidate.later.front();
      candidate.later.erase(candidate.later.begin());
      candidate.config.frames = std::uint32_t(candidate.later.size() + 1);
      candidate.config.frame = candidate.batch.frame;
      if (Fails(candidate)) c = std::move(candidate);
    }
  }

  // Every frame's records in turn.
  void ShrinkAllRecords(AdversarialCase& c) {
    ShrinkRecords(c, -1);
    for (std::size_t k = 0; k < c.later.size(); ++k) ShrinkRecords(c, std::ptrdiff_t(k));
  }

  // ddmin over the records of one frame (which: -1 for c.batch, else an index of c.later): try each of n chunks
  // alone, then each complement; on success restart from the smaller list, else split finer, until chunks are
  // single records.
  void ShrinkRecords(AdversarialCase& c, std::ptrdiff_t which) {
    std::size_t n = 2;
    while (FrameOf(c, which).records.size() >= 2 && !exhausted_) {
      const std::size_t size = FrameOf(c, which).records.size(), chunks = std::min(n, size);
      bool reduced = false;
      for (std::size_t pass = 0; pass < 2 && !reduced; ++pass) {
        for (std::size_t i = 0; i < chunks && !reduced; ++i) {
          const std::size_t begin = i * size / chunks, end = (i + 1) * size / chunks;
          std::vector<std::size_t> kept;
          for (std::size_t r = 0; r < size; ++r) {
            // pass 0: the chunk alone; pass 1: everything but the chunk
            if ((r >= begin && r < end) == (pass == 0)) kept.push_back(r);
          }
          if (pass == 1 && chunks == 2) continue;  // with two chunks, the complements are the chunks again
          AdversarialCase candidate = WithRecords(c, which, kept);
          if (Fails(candidate)) {
            c = std::move(candidate);
            n = pass == 0 ? 2 : std::max<std::size_t>(chunks - 1, 2);
            reduced = true;
          }
        }
      }
      if (reduced) continue;
      if (chunks >= size) break;
      n = std::min(2 * chunks, size);
    }
  }

  // Each simplification kept when the case still fails; one that makes the configuration invalid is skipped.
  void SimplifyConfig(AdversarialCase& c) {
    const auto attempt = [&](auto change) {
      AdversarialCase candidate = c;
      change(candidate);
      try {
        candidate.config.Validate();
        candidate.emulator.Validate();
      } catch (const ConfigError&) {
        return;
      }
      if (Fails(candidate)) c = std::move(candidate);
    };
    if (!keep_.eviction && c.config.eviction.enabled()) attempt([](AdversarialCase& a) { a.config.eviction = {}; });
    if (!keep_.compaction && c.config.compaction != Compaction::kNone) {
      attempt([](AdversarialCase& a) { a.config.compaction = Compaction::kNone; });
    }
    if (!keep_.temporal && c.config.temporal.mode != TemporalMode::kIntegrate) {
      attempt([](AdversarialCase& a) { a.config.temporal = {}; });
    }
    if (c.config.neighbour_search) {
      attempt([](AdversarialCase& a) {
        a.config.neighbour_search = false;
        if (a.config.levels == 1) a.config.min_count = 1;
      });
    }
    if (c.config.level_seed.enabled) attempt([](AdversarialCase& a) { a.config.level_seed = {}; });
    if (c.config.transport && !keep_.transport) attempt([](AdversarialCase& a) { a.config.transport = false; });
    if (!c.batch.own_light.empty()) {
      attempt([](AdversarialCase& a) {
        a.batch.own_light.clear();
        for (RecordBatch& frame : a.later) frame.own_light.clear();
      });
    }
    if (c.config.interpolation.enabled()) attempt([](AdversarialCase& a) { a.config.interpolation = {}; });
    if (c.config.second_moments) {
      attempt([](AdversarialCase& a) {
        a.config.second_moments = false;
        a.config.interpolation = {};
      });
    }
    if (c.config.levels > 1) {
      attempt([](AdversarialCase& a) {
        a.config.levels = 1;
        if (!a.config.neighbour_search) a.config.min_count = 1;
      });
    }
    if (c.config.fixed_point_bits) attempt([](AdversarialCase& a) { a.config.fixed_point_bits.reset(); });
    if (c.config.fingerprint_bits != 32) attempt([](AdversarialCase& a) { a.config.fingerprint_bits = 32; });
    if (!keep_.key_identity && c.config.key_identity != KeyIdentity::kFingerprint) {
      attempt([](AdversarialCase& a) { a.config.key_identity = KeyIdentity::kFingerprint; });
    }
    if (!keep_.probing && c.config.probing != ProbeKind::kLinear)
      attempt([](AdversarialCase& a) { a.config.probing = ProbeKind::kLinear; });
    if (!keep_.accumulation && c.config.accumulation != Accumulation::kFixed64)
      attempt([](AdversarialCase& a) { a.config.accumulation = Accumulation::kFixed64; });
    if (c.emulator.mode == simt::Mode::kFaithful && c.emulator.schedule != "round-robin") {
      attempt([](AdversarialCase& a) { a.emulator.schedule = "round-robin"; });
    }
    if (c.emulator.spurious_cas > 0.0) attempt([](AdversarialCase& a) { a.emulator.spurious_cas = 0.0; });
    if (c.emulator.mode == simt::Mode::kFaithful && c.emulator.warp_size != 8)
      attempt([](AdversarialCase& a) { a.emulator.warp_size = 8; });
    for (std::uint32_t limit = 1; limit < c.config.probe_limit; ++limit) {
      const std::uint32_t before = c.config.probe_limit;
      attempt([limit](AdversarialCase& a) { a.config.probe_limit = limit; });
      if (c.config.probe_limit != before) break;
    }
  }

  std::uint64_t checks() const { return checks_; }
  bool exhausted() const { return exhausted_; }

 private:
  // which: -1 for c.batch, else an index of c.later.
  static RecordBatch& FrameOf(AdversarialCase& c, std::ptrdiff_t which) {
    return which < 0 ? c.batch : c.later[std::size_t(which)];
  }
  // The frame's records at `kept`, and their scattered vertices and own lights with them (one per record: a case has
  // no deeper ones).
  static AdversarialCase WithRecords(const AdversarialCase& c, std::ptrdiff_t which,
                                     const std::vector<std::size_t>& kept) {
    AdversarialCase candidate = c;
    RecordBatch& frame = FrameOf(candidate, which);
    const RecordBatch& from = which < 0 ? c.batch : c.later[std::size_t(which)];
    frame.records.clear();
    frame.scattered.clear();
    frame.own_light.clear();
    for (const std::size_t i : kept) {
      frame.records.push_back(from.records[i]);
      if (!from.scattered.empty()) frame.scattered.push_back(from.scattered[i]);
      if (!from.own_light.empty()) frame.own_light.push_back(from.own_light[i]);
    }
    frame.width = std::uint32_t(frame.records.size());
    frame.height = 1;
    frame.samples_per_pixel = 1;
    return candidate;
  }

  const CaseFailsFn& fails_;
  ShrinkKeeps keep_;
  std::uint64_t max_checks_;
  std::uint64_t checks_ = 0;
  bool exhausted_ = false;
};

}  // namespace

ShrinkResult ShrinkCase(const AdversarialCase& failing, const CaseFailsFn& fails, ShrinkKeeps keep,
                        std::uint64_t max_checks) {
  Shrinker shrinker(fails, keep, max_checks);
  AdversarialCase c = failing;
  shrinker.ShrinkFrames(c);
  shrinker.ShrinkAllRecords(c);
  const AdversarialCase before_config = c;
  shrinker.SimplifyConfig(c);
  // A simpler configuration may need fewer records (a shorter window fills with fewer keys) or frames.
  if (c.config.ToString() != before_config.config.ToString() ||
      c.emulator.schedule != before_config.emulator.schedule) {
    shrinker.ShrinkFrames(c);
    shrinker.ShrinkAllRecords(c);
  }
  return {std::move(c), shrinker.checks(), shrinker.exhausted()};
}

}  // namespace hpsf
