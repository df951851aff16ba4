#include "verifier/contract/image_check.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/fixed_point_scale.h"
#include "core/input_check.h"
#include "core/resolve.h"

namespace hpsf {
namespace {

constexpr std::size_t kShown = 20;
constexpr double kUnitRoundoff = 0x1p-23;  // float atomics: not promised round-to-nearest (docs/design/contract.md)

// Per slot: the exact sum and the sum of magnitudes of the contributions placed there, per channel, by the records
// and the deeper ones (several filtered bounces: they share the table).
struct SlotSums {
  std::vector<glm::dvec3> exact, magnitude;
  std::vector<std::uint64_t> records;  // placed this frame
};

SlotSums SumsByPlacement(const RecordBatch& batch, const HashedRun& run) {
  SlotSums s{std::vector<glm::dvec3>(run.table.capacity, glm::dvec3(0.0)),
             std::vector<glm::dvec3>(run.table.capacity, glm::dvec3(0.0)),
             std::vector<std::uint64_t>(run.table.capacity, 0)};
  const TableRecords table(batch);
  const std::size_t n = table.size();
  for (std::size_t touch = 0; touch < n * run.table.levels; ++touch) {
    const std::size_t i = touch % n;
    const std::uint32_t slot = LevelPlacement(run, i, std::uint32_t(touch / n));
    if (slot >= run.table.capacity) continue;
    ++s.records[slot];
    const glm::dvec3 c(table.all()[i].contribution);
    s.exact[slot] += c;  // doubles: 29 bits beyond float's, far below the bound
    s.magnitude[slot] += glm::abs(c);
  }
  return s;
}

std::string Describe(std::size_t pixel, int channel, float got, double expected, double bound) {
  char text[160];
  if (bound > 0.0) {
    std::snprintf(text, sizeof text, "pixel %zu channel %d: %.9g, its table gives %.17g within %.3g", pixel, channel,
                  double(got), expected, bound);
  } else {
    std::snprintf(text, sizeof text, "pixel %zu channel %d: %.9g, its table gives %.9g exactly", pixel, channel,
                  double(got), expected);
  }
  return text;
}

void CheckFixed(const RecordBatch& batch, const HashedRun& run, std::vector<std::string>& out) {
  std::vector<std::optional<glm::dvec3>> averages(batch.records.size());
  for (std::size_t i = 0; i < batch.records.size(); ++i)
    averages[i] = ResolvedAverage(run, batch.records[i], i, ResolvedSlot(run, i));
  const Image resolved = ResolvePixels(batch, averages);
  for (std::size_t p = 0; p < resolved.pixels.size() && out.size() < kShown; ++p) {
    for (int c = 0; c < 3; ++c) {
      if (std::bit_cast<std::uint32_t>(run.image.pixels[p][c]) != std::bit_cast<std::uint32_t>(resolved.pixels[p][c])) {
        out.push_back(Describe(p, c, run.image.pixels[p][c], resolved.pixels[p][c], 0.0));
      }
    }
  }
}

void CheckFloat(const RecordBatch& batch, const HashedRun& run, const HashTableDump* before,
                std::vector<std::string>& out) {
  const SlotSums sums = SumsByPlacement(batch, run);
  const std::uint32_t spp = batch.samples_per_pixel;
  for (std::size_t p = 0; p < run.image.pixels.size() && out.size() < kShown; ++p) {
    glm::dvec3 expected(0.0), bound(0.0), magnitude(0.0);
    for (std::uint32_t s = 0; s < spp; ++s) {
      const Record& r = batch.records[p * spp + s];
      if (CheckRecordInputs(r) != InputVerdict::kAccepted) continue;
      const shared::LevelChoice chosen = ResolvedSlot(run, p * spp + s);
      const std::uint32_t slot = chosen.slot;
      std::optional<glm::dvec3> average;
      // A slot that carried samples into the frame, or was seeded from another level (core/level_seed.h), holds more
      // than this frame's records: level 2 bounds its sum.
      const bool carried =
          slot < run.table.capacity &&
          ((before && before->counts[slot] > 0) || (run.seeded > 0 && run.table.counts[slot] != sums.records[slot]));
      // A record that searched reads several slots: held to the resolve of the table's own sums, as a carried slot.
      if (carried || Searches(run.neighbour_search, chosen, run.table.capacity)) {
        average = ResolvedAverage(run, r, p * spp + s, chosen);
      } else if (slot < run.table.capacity) {
        const double n = double(run.table.counts[slot]), k = n - 1.0;
        average = sums.exact[slot] / n;
        // --interpolation: the weight as the backend computes it, from its table's words; the bound below, times
        // w <= 1, still holds.
        if (run.interpolation.enabled()) {
          average = Interpolated(run.interpolation, SlotWeight(run.interpolation, run.table, slot), *average,
                                 OwnLight(run.own_light, r, p * spp + s));
        }
        // The slot's float sum is within gamma(n - 1) * sum|c| of the exact one; divided by n, times |throughput|.
        bound += glm::abs(glm::dvec3(r.throughput)) * (k * kUnitRoundoff / (1.0 - k * kUnitRoundoff)) *
                 sums.magnitude[slot] / n;
      }
      const glm::dvec3 value = AcceptedRecordValue(r, average ? &*average : nullptr);
      expected += value;
      magnitude += glm::abs(value);
    }
    for (int c = 0; c < 3; ++c) {
      // The pixel mean, then its rounding to float (half an ulp, relative 2^-24) and slack for the double
      // arithmetic of the resolve on host or device (relative 2^-40 of the magnitudes summed).
      const double e = expected[c] / spp;
      const double allowed = bound[c] / spp + std::abs(e) * 0x1p-24 + magnitude[c] / spp * 0x1p-40;
      const float got = run.image.pixels[p][c];
      if (!(std::abs(double(got) - e) <= allowed)) out.push_back(Describe(p, c, got, e, allowed));
    }
  }
}

}  // namespace

std::vector<std::string> CheckImageAgainstTable(const RecordBatch& batch, const HashedRun& run,
                                                const HashTableDump* before) {
  std::vector<std::string> out;
  if (run.image.pixels.size() != std::size_t(batch.width) * batch.height)
    return {"the image does not have the batch's size"};
  if (IntegerSums(run.table.accumulation)) {
    CheckFixed(batch, run, out);
  } else {
    CheckFloat(batch, run, before, out);
  }
  return out;
}

}  // namespace hpsf
