// Deterministic record and config generators for key-path properties. Random numbers come from the project's
// counter RNG, keyed by a seed that rapidcheck draws, so a failing batch is reproduced by its seed. Besides
// uniform records they construct the hard cases on purpose: positions within ulps of a cell or level boundary
// (solved back through the jitter), far from the origin, normals with signed-zero components, tiny and
// denormal footprints, unkeyable records.
#ifndef HPSF_VERIFIER_GENERATORS_RECORD_GENERATORS_H
#define HPSF_VERIFIER_GENERATORS_RECORD_GENERATORS_H

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/filter_config.h"
#include "core/record.h"
#include "core/shared/key_params.h"

namespace hpsf::testing {

enum class RecordKind {
  kUniform,
  kCellBoundary,   // the jittered position within a few ulps of a cell boundary
  kLevelBoundary,  // the jittered path length within a few ulps of a level boundary
  kFar1e5,
  kFar1e7,
  kSignedZeroNormal,
  kNoVertex,
};
const char* ToString(RecordKind kind);
using hpsf::ToString;  // keep the core overloads visible beside this one

// A config plus the camera's footprint scale: everything the key path reads.
struct KeyCase {
  FilterConfig config;
  float footprint_scale = 0.01f;
  shared::KeyParams Params(std::uint32_t record_count) const;
  std::string ToString() const;
};

class RecordGenerator {
 public:
  explicit RecordGenerator(std::uint32_t seed) : seed_(seed) {}

  KeyCase Case();  // any config, including tiny and denormal footprints and cell sizes that make unkeyables
  Record Make(RecordKind kind, const shared::KeyParams& params);
  std::vector<Record> Batch(RecordKind kind, const shared::KeyParams& params, std::size_t count);
  std::vector<Record> MixedBatch(const shared::KeyParams& params, std::size_t count);

  std::uint32_t Bits();
  float Uniform(float low, float high);
  int UniformInt(int low, int high);  // inclusive

 private:
  glm::vec3 UnitNormal();
  glm::vec3 SignedZeroNormal();
  VertexSample Vertex(glm::vec3 center, float extent);
  Record SolveOntoCellBoundary(VertexSample v, const shared::KeyParams& params);
  Record SolveOntoLevelBoundary(VertexSample v, const shared::KeyParams& params);

  std::uint32_t seed_;
  std::uint32_t counter_ = 0;
  std::uint32_t pixel_ = 0;
};

// The jittered position and its cell quotient, recomputed from the shared code, to check the generators reach
// the boundaries they aim for.
struct KeyPathTrace {
  glm::vec3 jittered;
  float path_length;   // d' after the jitter
  float inverse_size;  // 1 / cell size of the jittered position
  glm::vec3 quotient;  // q = x' * inverse_size
};
KeyPathTrace TraceKeyPath(const Record& record, const shared::KeyParams& params);

// Distance in ulps from x to the nearest float that is an integer (for q) or a power of two (for w).
int UlpsToInteger(float x);
int UlpsToPowerOfTwo(float x);

}  // namespace hpsf::testing

#endif  // HPSF_VERIFIER_GENERATORS_RECORD_GENERATORS_H
