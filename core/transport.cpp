#include "core/transport.h"

#include <atomic>
#include <string>

#include "core/error.h"
#include "core/input_check.h"
#include "core/neighbour_search.h"
#include "core/shared/transport.h"

namespace hpsf {

void CheckScatteredShape(const RecordBatch& batch) {
  const std::size_t records = batch.records.size() + batch.deeper.size();
  if (!batch.scattered.empty() && batch.scattered.size() != records) {
    throw InputError("record batch: " + std::to_string(batch.scattered.size()) + " scattered vertices for " +
                     std::to_string(records) + " records with the deeper ones (none, or one per record)");
  }
}

TransportResult TransportBatch(const RecordBatch& batch, const KeyParams& params, Accumulation accumulation,
                               int fixed_point_bits, const TransportLookup& lookup, ScatteredKeyFn key_of,
                               const RangeLoop& loop) {
  CheckScatteredShape(batch);
  const std::size_t n = batch.records.size();
  // The records and the deeper ones copied to be transported; the scattered vertices are not needed past this step.
  RecordBatch transported{batch.width,         batch.height, batch.samples_per_pixel,
                          batch.fov_y_radians, batch.frame,  batch.records,
                          batch.deeper,        {},           batch.own_light};
  TransportResult result{
      std::move(transported), std::vector<std::uint32_t>(n + batch.deeper.size(), kNothingTransported), {}};
  // Counted per range and added up: sums of integers, the same in any order.
  std::atomic<std::uint64_t> scattered{0}, unkeyable{0}, found_cells{0}, missed{0};
  const auto transport_range = [&](std::size_t begin, std::size_t end) {
    TransportStats local;
    for (std::size_t i = begin; i < end; ++i) {
      Record& r = i < n ? result.batch.records[i] : result.batch.deeper[i - n];
      const Record& s = batch.scattered[i];
      if (!shared::RecordHasVertex(r) || !shared::RecordHasVertex(s)) continue;
      if (CheckRecordInputs(r) != InputVerdict::kAccepted || CheckRecordInputs(s) != InputVerdict::kAccepted) continue;
      ++local.scattered;
      const KeyResult key = key_of ? key_of(params, s, r) : shared::ComputeKey(params, s);
      if (key.status == shared::kKeyUnkeyable) {
        ++local.unkeyable;
        continue;
      }
      const std::optional<FoundCell> found = lookup(key.words);
      if (!found || found->state.count == 0) {
        ++local.missed;
        continue;
      }
      ++local.found;
      StencilTotal one;
      one.Add(found->state.fixed_sum, found->state.float_sum, found->state.count);
      const glm::vec3 light = shared::TransportedContribution(glm::vec3(r.contribution), glm::vec3(s.throughput),
                                                              one.Average(accumulation, fixed_point_bits));
      r.contribution = glm::vec4(light, 0.0f);
      result.read[i] = found->index;
    }
    scattered += local.scattered;
    unkeyable += local.unkeyable;
    found_cells += local.found;
    missed += local.missed;
  };
  if (loop) {
    loop(batch.scattered.size(), transport_range);
  } else {
    transport_range(0, batch.scattered.size());
  }
  result.stats = {scattered.load(), unkeyable.load(), found_cells.load(), missed.load()};
  return result;
}

}  // namespace hpsf
