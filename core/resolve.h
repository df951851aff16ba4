// The resolve pass every backend shares: a record's value is radiance_before + throughput * incident, where
// incident is its cell's average, or its own contribution when it has no cell (unkeyable, probe failure), and
// a record without a vertex has radiance_before alone. A pixel is the mean of its records in sample order.
// Rejected records contribute nothing. Nothing is lost, nothing divided by an albedo.
#ifndef HPSF_CORE_RESOLVE_H
#define HPSF_CORE_RESOLVE_H

#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/image.h"
#include "core/input_check.h"
#include "core/record.h"

namespace hpsf {

// An accepted record's value: radiance_before, plus throughput times its cell's average (or, without a cell,
// its own contribution) when it has a vertex. Backends that resolve in parallel sum these in sample order.
glm::dvec3 AcceptedRecordValue(const Record& r, const glm::dvec3* average);
// A pixel from the sum of its accepted records' values.
inline glm::vec3 PixelMean(const glm::dvec3& sum, std::uint32_t samples_per_pixel) {
  return glm::vec3(sum / double(samples_per_pixel));
}

// averages[i]: the average of record i's cell, or nullopt when the record has none.
Image ResolvePixels(const RecordBatch& batch, std::span<const std::optional<glm::dvec3>> averages);

// Throws InputError when the batch's records do not fill its image.
void CheckBatchShape(const RecordBatch& batch);

}  // namespace hpsf

#endif  // HPSF_CORE_RESOLVE_H
