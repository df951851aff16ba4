// fuzz_checker: the table checker's teeth. A correct table comes from a generated batch (fuzz_batch.h, the
// emulator in fast mode, which the checker must pass); then the input corrupts it once: flips or sets a tag,
// changes a count, one channel's sum or (with second moments) the square sum, moves a record's placement (to another
// slot, a probe failure, "not placed" or past the end), zeroes a slot or swaps two slots; or changes a key word, which
// only must not crash. A bug: the checker crashes, or misses a corruption that changes what the invariants describe.
// Those are all changes to the dump's bits, except a float32 sum moved within the bound gamma(n - 1) * sum|c| of its
// slot's exact sum (atomics may round anywhere inside it; docs/design/contract.md), or an empty slot's sum turned to
// -0.0, which is still zero. A corruption that leaves the dump as it was is none.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "core/hash_table.h"
#include "core/input_check.h"
#include "core/shared/second_moment.h"
#include "emulated/emulated_filter.h"
#include "tools/fuzz/fuzz_batch.h"
#include "verifier/checker/table_checker.h"

namespace hpsf {
namespace {

enum class Corruption {
  kFlipTagBits,
  kSetTag,
  kChangeCount,
  kChangeSum,
  kMovePlacement,
  kZeroSlot,
  kSwapSlots,
  kChangeKey,
  kChangeSquare,  // with second moments: one slot's square sum
  kMaxValue = kChangeSquare
};

struct Slot {
  SlotTag tag;
  std::uint64_t count;
  std::array<std::uint64_t, 3> fixed_sum;
  std::array<std::uint32_t, 3> float_bits;
  std::uint64_t square;  // with second moments: the fixed64 square sum, or the float32 one's bits
  bool operator==(const Slot&) const = default;
};

Slot SlotAt(const HashTableDump& t, std::uint32_t s) {
  Slot slot{t.tags[s], t.counts[s], {}, {}, 0};
  if (t.accumulation == Accumulation::kFixed64) slot.fixed_sum = t.fixed_sums[s];
  if (t.accumulation == Accumulation::kFloat32) {
    for (int c = 0; c < 3; ++c) slot.float_bits[c] = std::bit_cast<std::uint32_t>(t.float_sums[s][c]);
  }
  if (t.second_moments) {
    slot.square = t.accumulation == Accumulation::kFixed64 ? t.fixed_squares[s]
                                                           : std::bit_cast<std::uint32_t>(t.float_squares[s]);
  }
  return slot;
}

void SetSlot(HashTableDump& t, std::uint32_t s, const Slot& slot) {
  t.tags[s] = slot.tag;
  t.counts[s] = slot.count;
  if (t.accumulation == Accumulation::kFixed64) t.fixed_sums[s] = slot.fixed_sum;
  if (t.accumulation == Accumulation::kFloat32) {
    for (int c = 0; c < 3; ++c) t.float_sums[s][c] = std::bit_cast<float>(slot.float_bits[c]);
  }
  if (t.second_moments && t.accumulation == Accumulation::kFixed64) t.fixed_squares[s] = slot.square;
  if (t.second_moments && t.accumulation == Accumulation::kFloat32) {
    t.float_squares[s] = std::bit_cast<float>(std::uint32_t(slot.square));
  }
}

// Whether a float32 sum moved to `value` may still be what atomics rounding anywhere produce: within
// gamma(n - 1) * sum|c| of the exact sum of the n records placed in the slot, give or take a margin far below an
// ulp (the checker sums in double). An empty slot has no leeway: its sums are zero (-0.0 is zero too).
bool MayBeWithinFloatBound(const EmulatedRun& run, const RecordBatch& batch, std::uint32_t slot, int channel,
                           float value) {
  long double exact = 0, magnitude = 0;
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    if (run.placements[i] != slot) continue;
    exact += batch.records[i].contribution[channel];
    magnitude += std::fabs(batch.records[i].contribution[channel]);
    ++n;
  }
  if (n == 0) return value == 0.0f;
  if (!std::isfinite(value)) return false;
  const long double k = n - 1, u = 0x1p-23L;
  return std::fabs((long double)value - exact) <= k * u / (1 - k * u) * magnitude + std::fabs(exact) * 0x1p-40L;
}

// The same for a float32 square sum: its terms are the records' float squares (core/shared/second_moment.h).
bool MayBeWithinSquareBound(const EmulatedRun& run, const RecordBatch& batch, std::uint32_t slot, float value) {
  long double exact = 0;
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    if (run.placements[i] != slot) continue;
    exact += shared::SquareAsFloat(glm::vec3(batch.records[i].contribution));
    ++n;
  }
  if (n == 0) return value == 0.0f;
  if (!std::isfinite(value)) return false;
  const long double k = n - 1, u = 0x1p-23L;
  return std::fabs((long double)value - exact) <= k * u / (1 - k * u) * exact + exact * 0x1p-40L;
}

struct Corrupted {
  std::string what;
  bool must_flag = true;
};

Corrupted Corrupt(FuzzedDataProvider& input, const RecordBatch& batch, EmulatedRun& run) {
  HashTableDump& t = run.table;
  const bool fixed = t.accumulation == Accumulation::kFixed64;
  const std::uint32_t s = input.ConsumeIntegralInRange<std::uint32_t>(0, t.capacity - 1);
  const std::uint32_t record = input.ConsumeIntegralInRange<std::uint32_t>(0, std::uint32_t(batch.records.size() - 1));
  const std::string at = " at slot " + std::to_string(s);
  switch (input.ConsumeEnum<Corruption>()) {
    case Corruption::kFlipTagBits: {
      const std::uint32_t mask = input.ConsumeIntegral<std::uint32_t>();
      t.tags[s] ^= mask;
      return {"tag xor " + std::to_string(mask) + at, mask != 0};
    }
    case Corruption::kSetTag: {
      const SlotTag old = t.tags[s];
      t.tags[s] = input.ConsumeBool() ? run.keys[record].fingerprint : input.ConsumeIntegral<std::uint32_t>();
      return {"tag " + std::to_string(old) + " -> " + std::to_string(t.tags[s]) + at, t.tags[s] != old};
    }
    case Corruption::kChangeCount: {
      const std::uint64_t delta = input.ConsumeIntegral<std::uint64_t>();
      t.counts[s] += delta;
      return {"count + " + std::to_string(delta) + at, delta != 0};
    }
    case Corruption::kChangeSum: {
      const int channel = input.ConsumeIntegralInRange<int>(0, 2);
      const std::string what = "channel " + std::to_string(channel) + " sum";
      if (fixed) {
        const std::uint64_t delta = input.ConsumeIntegral<std::uint64_t>();
        t.fixed_sums[s][channel] += delta;
        return {what + " + " + std::to_string(delta) + at, delta != 0};
      }
      const std::uint32_t mask = input.ConsumeIntegral<std::uint32_t>();
      const float value = std::bit_cast<float>(std::bit_cast<std::uint32_t>(t.float_sums[s][channel]) ^ mask);
      t.float_sums[s][channel] = value;
      return {what + " bits xor " + std::to_string(mask) + at,
              mask != 0 && !MayBeWithinFloatBound(run, batch, s, channel, value)};
    }
    case Corruption::kMovePlacement: {
      const std::uint32_t old = run.placements[record];
      switch (input.ConsumeIntegralInRange<int>(0, 3)) {
        case 0:
          run.placements[record] = kProbeFailure;
          break;
        case 1:
          run.placements[record] = kNotPlaced;
          break;
        case 2:
          run.placements[record] = t.capacity + input.ConsumeIntegralInRange<std::uint32_t>(0, 4);
          break;
        default:
          run.placements[record] = s;
          break;
      }
      return {"record " + std::to_string(record) + " placement " + std::to_string(old) + " -> " +
                  std::to_string(run.placements[record]),
              run.placements[record] != old};
    }
    case Corruption::kZeroSlot: {
      const Slot old = SlotAt(t, s);
      SetSlot(t, s, Slot{});
      return {"zeroed slot" + at, !(old == Slot{})};
    }
    case Corruption::kSwapSlots: {
      const std::uint32_t other = input.ConsumeIntegralInRange<std::uint32_t>(0, t.capacity - 1);
      const Slot a = SlotAt(t, s), b = SlotAt(t, other);
      SetSlot(t, s, b);
      SetSlot(t, other, a);
      return {"swapped slots " + std::to_string(s) + " and " + std::to_string(other), !(a == b)};
    }
    case Corruption::kChangeKey: {
      KeyResult& key = run.keys[record];
      const std::uint32_t value = input.ConsumeIntegral<std::uint32_t>();
      switch (input.ConsumeIntegralInRange<int>(0, 2)) {
        case 0:
          key.slot0 = value;
          break;
        case 1:
          key.fingerprint = value;
          break;
        default:
          key.status = value;
          break;
      }
      return {"record " + std::to_string(record) + "'s key changed", false};
    }
    case Corruption::kChangeSquare: {
      if (!t.second_moments) return {"none", false};
      if (fixed) {
        const std::uint64_t delta = input.ConsumeIntegral<std::uint64_t>();
        t.fixed_squares[s] += delta;
        return {"square sum + " + std::to_string(delta) + at, delta != 0};
      }
      const std::uint32_t mask = input.ConsumeIntegral<std::uint32_t>();
      const float value = std::bit_cast<float>(std::bit_cast<std::uint32_t>(t.float_squares[s]) ^ mask);
      t.float_squares[s] = value;
      return {"square sum bits xor " + std::to_string(mask) + at,
              mask != 0 && !MayBeWithinSquareBound(run, batch, s, value)};
    }
  }
  return {"none", false};
}

std::vector<TableViolation> Check(const RecordBatch& batch, const EmulatedRun& run) {
  return CheckTable({run.table, batch.records, run.keys, run.placements});
}

[[noreturn]] void Fail(const FuzzCase& c, const std::string& problem, const std::vector<TableViolation>& violations) {
  std::fprintf(stderr, "fuzz_checker: %s\n", problem.c_str());
  for (const TableViolation& v : violations) std::fprintf(stderr, "  %s\n", v.ToString().c_str());
  std::fprintf(stderr, "%s", c.ToString().c_str());
  std::abort();
}

}  // namespace
}  // namespace hpsf

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hpsf;
  FuzzedDataProvider input(data, size);
  const FuzzCase c = DecodeFuzzCase(input);
  EmulatedRun run = EmulatedFilter(c.batch, c.config, c.fast);
  if (const std::vector<TableViolation> violations = Check(c.batch, run); !violations.empty()) {
    Fail(c, "the emulator's own table fails the checker", violations);
  }
  const Corrupted corrupted = Corrupt(input, c.batch, run);
  const std::vector<TableViolation> violations = Check(c.batch, run);
  if (corrupted.must_flag && violations.empty()) Fail(c, "missed a corruption: " + corrupted.what, violations);
  return 0;
}
