#include "tools/checks/case_shrinker.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "core/error.h"

namespace hpsf {
namespace {

class Shrinker {
 public:
  Shrinker(const CaseFailsFn& fails, bool keep_accumulation, std::uint64_t max_checks)
      : fails_(fails), keep_accumulation_(keep_accumulation), max_checks_(max_checks) {}

  bool Fails(const AdversarialCase& candidate) {
    if (checks_ >= max_checks_) {
      exhausted_ = true;
      return false;
    }
    ++checks_;
    return fails_(candidate);
  }

  // ddmin: try each of n chunks alone, then each complement; on success restart from the smaller list, else
  // split finer, until chunks are single records.
  void ShrinkRecords(AdversarialCase& c) {
    std::size_t n = 2;
    while (c.batch.records.size() >= 2 && !exhausted_) {
      const std::vector<Record> records = c.batch.records;
      const std::size_t size = records.size(), chunks = std::min(n, size);
      bool reduced = false;
      for (std::size_t pass = 0; pass < 2 && !reduced; ++pass) {
        for (std::size_t i = 0; i < chunks && !reduced; ++i) {
          const std::size_t begin = i * size / chunks, end = (i + 1) * size / chunks;
          std::vector<Record> kept;
          if (pass == 0) {  // the chunk alone
            kept.assign(records.begin() + std::ptrdiff_t(begin), records.begin() + std::ptrdiff_t(end));
          } else {  // everything but the chunk
            kept.assign(records.begin(), records.begin() + std::ptrdiff_t(begin));
            kept.insert(kept.end(), records.begin() + std::ptrdiff_t(end), records.end());
          }
          if (pass == 1 && chunks == 2) continue;  // with two chunks, the complements are the chunks again
          AdversarialCase candidate = WithRecords(c, std::move(kept));
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
    if (c.config.fingerprint_bits != 32) attempt([](AdversarialCase& a) { a.config.fingerprint_bits = 32; });
    if (!keep_accumulation_ && c.config.accumulation != Accumulation::kFixed64) attempt([](AdversarialCase& a) { a.config.accumulation = Accumulation::kFixed64; });
    if (c.emulator.mode == simt::Mode::kFaithful && c.emulator.schedule != "round-robin") {
      attempt([](AdversarialCase& a) { a.emulator.schedule = "round-robin"; });
    }
    if (c.emulator.mode == simt::Mode::kFaithful && c.emulator.warp_size != 8) attempt([](AdversarialCase& a) { a.emulator.warp_size = 8; });
    for (std::uint32_t limit = 1; limit < c.config.probe_limit; ++limit) {
      const std::uint32_t before = c.config.probe_limit;
      attempt([limit](AdversarialCase& a) { a.config.probe_limit = limit; });
      if (c.config.probe_limit != before) break;
    }
  }

  std::uint64_t checks() const { return checks_; }
  bool exhausted() const { return exhausted_; }

 private:
  static AdversarialCase WithRecords(const AdversarialCase& c, std::vector<Record> records) {
    AdversarialCase candidate = c;
    candidate.batch.records = std::move(records);
    candidate.batch.width = std::uint32_t(candidate.batch.records.size());
    candidate.batch.height = 1;
    candidate.batch.samples_per_pixel = 1;
    return candidate;
  }

  const CaseFailsFn& fails_;
  bool keep_accumulation_;
  std::uint64_t max_checks_;
  std::uint64_t checks_ = 0;
  bool exhausted_ = false;
};

}  // namespace

ShrinkResult ShrinkCase(const AdversarialCase& failing, const CaseFailsFn& fails, bool keep_accumulation,
                        std::uint64_t max_checks) {
  Shrinker shrinker(fails, keep_accumulation, max_checks);
  AdversarialCase c = failing;
  shrinker.ShrinkRecords(c);
  const AdversarialCase before_config = c;
  shrinker.SimplifyConfig(c);
  // A simpler configuration may need fewer records (a shorter window fills with fewer keys).
  if (c.config.ToString() != before_config.config.ToString() || c.emulator.schedule != before_config.emulator.schedule) {
    shrinker.ShrinkRecords(c);
  }
  return {std::move(c), shrinker.checks(), shrinker.exhausted()};
}

}  // namespace hpsf
