#include "core/record.h"

#include "core/format.h"
#include "core/octahedral.h"
#include "core/tangent_frame.h"

namespace hpsf {
namespace {

glm::vec4 Pad(glm::vec3 v, float w = 0.0f) { return glm::vec4(v, w); }

}  // namespace

Record MakeVertexRecord(const VertexSample& vertex) {
  const TangentFrame frame = DuffTangentFrame(vertex.normal);
  Record r{};
  r.position = Pad(vertex.position, vertex.d_prefix);
  r.normal = Pad(vertex.normal);
  r.tangent = Pad(frame.tangent);
  r.bitangent = Pad(frame.bitangent);
  r.previous = Pad(vertex.previous);
  r.contribution = Pad(vertex.contribution);
  r.throughput = Pad(vertex.throughput);
  r.radiance_before = Pad(vertex.radiance_before);
  r.path =
      glm::uvec4(vertex.pixel, vertex.sample, shared::kRecordHasVertex | (vertex.bounce << shared::kRecordBounceShift),
                 PackOctahedral16(vertex.normal));
  return r;
}

Record MakeRecordWithoutVertex(std::uint32_t pixel, std::uint32_t sample, glm::vec3 radiance_before) {
  Record r{};
  r.radiance_before = Pad(radiance_before);
  r.path = glm::uvec4(pixel, sample, 0u, 0u);
  return r;
}

std::string ToString(const Record& r) {
  std::string s = "[ Record pixel: " + std::to_string(r.path.x) + " sample: " + std::to_string(r.path.y);
  if (!shared::RecordHasVertex(r))
    return s + " no vertex radiance_before: " + FormatVec3(glm::vec3(r.radiance_before)) + " ]";
  return s + " bounce: " + std::to_string(shared::RecordBounce(r)) + " x: " + FormatVec3(glm::vec3(r.position)) +
         " d_prefix: " + FormatFloat(r.position.w) + " n: " + FormatVec3(glm::vec3(r.normal)) +
         " T: " + FormatVec3(glm::vec3(r.tangent)) + " B: " + FormatVec3(glm::vec3(r.bitangent)) +
         " x_prev: " + FormatVec3(glm::vec3(r.previous)) + " octahedral: " + FormatHex(r.path.w) +
         " contribution: " + FormatVec3(glm::vec3(r.contribution)) +
         " throughput: " + FormatVec3(glm::vec3(r.throughput)) +
         " radiance_before: " + FormatVec3(glm::vec3(r.radiance_before)) + " ]";
}

TableRecords::TableRecords(const RecordBatch& batch) {
  if (batch.deeper.empty()) {
    all_ = batch.records;
    return;
  }
  joined_.reserve(batch.records.size() + batch.deeper.size());
  joined_.insert(joined_.end(), batch.records.begin(), batch.records.end());
  joined_.insert(joined_.end(), batch.deeper.begin(), batch.deeper.end());
  all_ = joined_;
}

glm::dvec3 OwnLight(const std::vector<glm::vec4>& own_light, const Record& record, std::size_t i) {
  const glm::vec4& own = own_light.empty() ? record.contribution : own_light[i];
  return glm::dvec3(own.x, own.y, own.z);
}

glm::dvec3 OwnLight(const RecordBatch& batch, std::size_t i) { return OwnLight(batch.own_light, batch.records[i], i); }

}  // namespace hpsf
