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

// averages[i]: the average of record i's cell, or nullopt when the record has none.
Image ResolvePixels(const RecordBatch& batch, std::span<const std::optional<glm::dvec3>> averages);

// Throws InputError when the batch's records do not fill its image.
void CheckBatchShape(const RecordBatch& batch);

}  // namespace hpsf

#endif  // HPSF_CORE_RESOLVE_H
