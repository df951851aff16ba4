#include "core/resolve.h"

#include "core/error.h"

namespace hpsf {
namespace {

glm::dvec3 D(glm::vec4 v) { return glm::dvec3(v.x, v.y, v.z); }

}  // namespace

void CheckBatchShape(const RecordBatch& batch) {
  if (std::uint64_t(batch.width) * batch.height * batch.samples_per_pixel != batch.records.size()) {
    throw InputError("record batch: " + std::to_string(batch.records.size()) + " records do not fill a " +
                     std::to_string(batch.width) + "x" + std::to_string(batch.height) + " image at " +
                     std::to_string(batch.samples_per_pixel) + " samples per pixel");
  }
}

glm::dvec3 AcceptedRecordValue(const Record& r, const glm::dvec3* average) {
  glm::dvec3 value = D(r.radiance_before);
  if (shared::RecordHasVertex(r)) value += D(r.throughput) * (average ? *average : D(r.contribution));
  return value;
}

Image ResolvePixels(const RecordBatch& batch, std::span<const std::optional<glm::dvec3>> averages) {
  CheckBatchShape(batch);
  Image image(batch.width, batch.height);
  const std::size_t spp = batch.samples_per_pixel;
  for (std::size_t pixel = 0; pixel < image.pixels.size(); ++pixel) {
    glm::dvec3 sum(0.0);
    for (std::size_t s = 0; s < spp; ++s) {
      const std::size_t i = pixel * spp + s;
      const Record& r = batch.records[i];
      if (CheckRecordInputs(r) != InputVerdict::kAccepted) continue;
      sum += AcceptedRecordValue(r, averages[i] ? &*averages[i] : nullptr);
    }
    image.pixels[pixel] = PixelMean(sum, batch.samples_per_pixel);
  }
  return image;
}

}  // namespace hpsf
