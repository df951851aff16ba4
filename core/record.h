// Sample records on the host: the shared GPU layout, a batch with the image it came from, and builders that
// compute the host-side fields (tangent frame, octahedral normal) once.
#ifndef HPSF_CORE_RECORD_H
#define HPSF_CORE_RECORD_H

#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/shared/record_layout.h"

namespace hpsf {

using Record = shared::Record;
static_assert(sizeof(Record) == 144 && std::is_standard_layout_v<Record>, "Record must match the std430 layout");

// One camera sample's filter vertex, before the host derives the rest of the record.
struct VertexSample {
  std::uint32_t pixel = 0;
  std::uint32_t sample = 0;
  std::uint32_t bounce = 0;  // index of the filter vertex along the path, 0 for the primary hit
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  // unit, facing the incoming ray
  glm::vec3 previous{0.0f};
  float d_prefix = 0.0f;
  glm::vec3 contribution{0.0f};
  glm::vec3 throughput{0.0f};
  glm::vec3 radiance_before{0.0f};
};

Record MakeVertexRecord(const VertexSample& vertex);
// A sample without a filter vertex (sky hit, path ended): it carries radiance_before only.
Record MakeRecordWithoutVertex(std::uint32_t pixel, std::uint32_t sample, glm::vec3 radiance_before);

// Every camera sample of one image, one record each, in (pixel, sample) order.
struct RecordBatch {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t samples_per_pixel = 0;
  double fov_y_radians = 0.0;  // the camera's, for the footprint scale (core/footprint.h)
  std::uint32_t frame = 0;     // the frame traced: its keyframes and random numbers, and the filter's config.frame
  std::vector<Record> records;
  // Several filtered bounces (core/transport.h). `deeper`: records of vertices further along the paths, added to the
  // table like any record but resolved into no pixel (their radiance_before and throughput are not read).
  // `scattered`: none, or one per record of `records` then `deeper`, the vertex its path scattered to from its
  // filter vertex, as a record keyed like any (its position, frame, previous vertex, path length, pixel, sample and
  // bounce) whose throughput is the transport weight: the throughput from the filter vertex to it times its albedo.
  // Its contribution and radiance_before are not read; where a path scattered nowhere it has no vertex flag.
  std::vector<Record> deeper;
  std::vector<Record> scattered;
  // None, or one per record of `records`: the light its pixel shows as the record's own where that differs from the
  // contribution its cell adds (adaptive path graphs, core/path_graph.h: the cut path's light, while the table adds
  // the path's in full). Read by the resolve's interpolation only; rgb, a: 0.
  std::vector<glm::vec4> own_light;
};

// What the resolve blends with a record's cell as its own light: own_light[i] where the batch has them, else the
// record's contribution.
glm::dvec3 OwnLight(const RecordBatch& batch, std::size_t i);
// The same from a run's copy of own_light (core/hashed_run.h).
glm::dvec3 OwnLight(const std::vector<glm::vec4>& own_light, const Record& record, std::size_t i);

// The records a frame adds to its table, in order: `records` then `deeper`. A view of `records` where there are no
// deeper records, else a copy of both.
class TableRecords {
 public:
  explicit TableRecords(const RecordBatch& batch);
  std::span<const Record> all() const { return all_; }
  std::size_t size() const { return all_.size(); }

 private:
  std::vector<Record> joined_;
  std::span<const Record> all_;
};

std::string ToString(const Record& record);

}  // namespace hpsf

#endif  // HPSF_CORE_RECORD_H
