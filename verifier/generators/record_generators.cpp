#include "verifier/generators/record_generators.h"

#include <array>
#include <bit>
#include <cmath>

#include "core/format.h"
#include "core/shared/key.h"

namespace hpsf::testing {
namespace {

float StepUlps(float x, int ulps) {
  for (; ulps > 0; --ulps) x = std::nextafter(x, INFINITY);
  for (; ulps < 0; ++ulps) x = std::nextafter(x, -INFINITY);
  return x;
}

struct JitterSetup {
  float amplitude;
  float inverse_size;
};

// The amplitude of the jitter and the cell size of the key path for this record, as the shared code computes them.
JitterSetup Setup(const Record& r, const shared::KeyParams& p) {
  if (p.lod_enabled == 0u) return {p.jitter_scale * p.cell_size, p.inverse_cell_size};
  const glm::vec3 x(r.position), x_prev(r.previous);
  const int level =
      shared::LevelOfDetail(p.footprint_scale, shared::PathLength(r.position.w, x, x_prev), p.level_min, p.level_max);
  return {shared::Flush(p.jitter_scale * shared::PowerOfTwo(level)), 0.0f};
}

}  // namespace

const char* ToString(RecordKind kind) {
  switch (kind) {
    case RecordKind::kUniform:
      return "uniform";
    case RecordKind::kCellBoundary:
      return "cell-boundary";
    case RecordKind::kLevelBoundary:
      return "level-boundary";
    case RecordKind::kFar1e5:
      return "far-1e5";
    case RecordKind::kFar1e7:
      return "far-1e7";
    case RecordKind::kSignedZeroNormal:
      return "signed-zero-normal";
    case RecordKind::kNoVertex:
      return "no-vertex";
  }
  return "?";
}

shared::KeyParams KeyCase::Params(std::uint32_t record_count) const {
  return MakeKeyParams(config, footprint_scale, record_count);
}

std::string KeyCase::ToString() const {
  return "[ KeyCase footprint_scale: " + FormatFloatBits(footprint_scale) + " config: " + config.ToString() + " ]";
}

std::uint32_t RecordGenerator::Bits() {
  shared::RngCounter c{seed_, 0xC0FFEEu, counter_++, 0u, 0u};
  return shared::RandomBits(c, 0u);
}

float RecordGenerator::Uniform(float low, float high) { return low + (high - low) * shared::BitsToUnitFloat(Bits()); }

int RecordGenerator::UniformInt(int low, int high) { return low + int(Bits() % std::uint32_t(high - low + 1)); }

KeyCase RecordGenerator::Case() {
  KeyCase c;
  FilterConfig& f = c.config;
  f.seed = Bits();
  f.frame = Bits() % 4u;
  f.jitter_scale = std::array{0.0f, 0.5f, 1.0f, 2.0f, Uniform(0.0f, 3.0f)}[Bits() % 5u];
  f.normal = std::array{NormalKey{NormalMode::kNone, 0}, NormalKey{NormalMode::kSign, 0},
                        NormalKey{NormalMode::kOctahedral, std::uint32_t(UniformInt(1, 16))}}[Bits() % 3u];
  f.normal_in_index = (Bits() & 1u) != 0u;
  f.capacity = 1u << UniformInt(1, 31);
  f.probe_limit = 1;
  f.fingerprint_bits = std::uint32_t(UniformInt(8, 32));
  f.level_min = UniformInt(-126, 0);
  f.level_max = UniformInt(f.level_min, 126);
  if (Bits() % 4u == 0u) {
    f.level_min = -126;
    f.level_max = 126;
  }
  f.lod = Bits() % 4u != 0u;
  // Cell sizes from tiny (most records unkeyable) to huge; footprints from denormal products to large.
  f.cell_size = std::array{
      1.0f, 0.37f, 1e-4f, 1e-30f, std::ldexp(1.0f, UniformInt(-100, 100)), Uniform(0.01f, 50.0f)}[Bits() % 6u];
  c.footprint_scale = std::array{0.01f, 1e-3f, Uniform(1e-4f, 0.1f), 1e-30f, 1e-38f, 0.0f, 16.0f}[Bits() % 7u];
  return c;
}

glm::vec3 RecordGenerator::UnitNormal() {
  // Uniform on the sphere from two exact uniforms, normalized in double and rounded once.
  const double z = 2.0 * shared::BitsToUnitFloat(Bits()) - 1.0, phi = 2.0 * M_PI * shared::BitsToUnitFloat(Bits());
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return glm::vec3(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z));
}

glm::vec3 RecordGenerator::SignedZeroNormal() {
  const float zero_x = (Bits() & 1u) ? -0.0f : 0.0f, zero_y = (Bits() & 1u) ? -0.0f : 0.0f;
  const float one = (Bits() & 1u) ? -1.0f : 1.0f;
  glm::vec3 n(zero_x, zero_y, one);
  const int axis = UniformInt(0, 2);
  std::swap(n[axis], n[2]);
  return n;
}

VertexSample RecordGenerator::Vertex(glm::vec3 center, float extent) {
  VertexSample v;
  v.pixel = pixel_++;
  v.sample = Bits() % 64u;
  v.bounce = Bits() % 8u;
  v.position = center + glm::vec3(Uniform(-extent, extent), Uniform(-extent, extent), Uniform(-extent, extent));
  v.normal = UnitNormal();
  v.previous = center + glm::vec3(Uniform(-extent, extent), Uniform(-extent, extent), Uniform(-extent, extent));
  v.d_prefix = (Bits() & 1u) ? 0.0f : Uniform(0.0f, 4.0f * extent);
  v.contribution = glm::vec3(Uniform(0.0f, 2.0f), Uniform(0.0f, 2.0f), Uniform(0.0f, 2.0f));
  v.throughput = glm::vec3(Uniform(0.0f, 1.0f), Uniform(0.0f, 1.0f), Uniform(0.0f, 1.0f));
  v.radiance_before = glm::vec3(Uniform(0.0f, 1.0f));
  return v;
}

Record RecordGenerator::SolveOntoCellBoundary(VertexSample v, const shared::KeyParams& p) {
  // x' = x + o with o fixed by the pre-jitter level: aim x' at a cell boundary, solve back for x, then step a
  // few ulps so both sides of the boundary are reached.
  const int axis = UniformInt(0, 2);
  for (int iteration = 0; iteration < 2; ++iteration) {
    const Record r = MakeVertexRecord(v);
    const KeyPathTrace trace = TraceKeyPath(r, p);
    if (!(std::abs(trace.quotient[axis]) < 0x1p30f)) break;  // no int32 cell to aim at: stays unkeyable
    const float boundary = std::round(trace.quotient[axis]) * (1.0f / trace.inverse_size);
    v.position[axis] = boundary - (trace.jittered[axis] - v.position[axis]);
  }
  v.position[axis] = StepUlps(v.position[axis], UniformInt(-3, 3));
  return MakeVertexRecord(v);
}

Record RecordGenerator::SolveOntoLevelBoundary(VertexSample v, const shared::KeyParams& p) {
  // d' = d_prefix + max|x' - x_prev|: aim d' at 2^m / footprint through d_prefix, iterating because the
  // pre-jitter level (and so the jitter) may move with it.
  if (p.footprint_scale == 0.0f || p.lod_enabled == 0u) return MakeVertexRecord(v);
  const KeyPathTrace start = TraceKeyPath(MakeVertexRecord(v), p);
  // Aim above the current length, since d_prefix can grow without bound but shrink only to 0.
  const float w = start.path_length * p.footprint_scale;
  if (!(std::isnormal(w) && w < 0x1p120f)) return MakeVertexRecord(v);
  const float target = std::ldexp(1.0f, std::ilogb(w) + UniformInt(1, 2)) / p.footprint_scale;
  if (!std::isfinite(target)) return MakeVertexRecord(v);
  for (int iteration = 0; iteration < 3; ++iteration) {
    const KeyPathTrace trace = TraceKeyPath(MakeVertexRecord(v), p);
    v.d_prefix = std::max(0.0f, v.d_prefix + (target - trace.path_length));
  }
  v.d_prefix = std::max(0.0f, StepUlps(v.d_prefix, UniformInt(-3, 3)));
  return MakeVertexRecord(v);
}

Record RecordGenerator::Make(RecordKind kind, const shared::KeyParams& p) {
  switch (kind) {
    case RecordKind::kUniform:
      return MakeVertexRecord(Vertex(glm::vec3(0.0f), 1000.0f));
    case RecordKind::kCellBoundary:
      return SolveOntoCellBoundary(Vertex(glm::vec3(0.0f), 100.0f), p);
    case RecordKind::kLevelBoundary:
      return SolveOntoLevelBoundary(Vertex(glm::vec3(0.0f), 100.0f), p);
    case RecordKind::kFar1e5:
      return MakeVertexRecord(Vertex(glm::vec3(1e5f, -1e5f, 1e5f), 500.0f));
    case RecordKind::kFar1e7:
      return MakeVertexRecord(Vertex(glm::vec3(-1e7f, 1e7f, 1e7f), 500.0f));
    case RecordKind::kSignedZeroNormal: {
      VertexSample v = Vertex(glm::vec3(0.0f), 10.0f);
      v.normal = SignedZeroNormal();
      return MakeVertexRecord(v);
    }
    case RecordKind::kNoVertex:
      return MakeRecordWithoutVertex(pixel_++, Bits() % 64u, glm::vec3(Uniform(0.0f, 5.0f)));
  }
  return Record{};
}

std::vector<Record> RecordGenerator::Batch(RecordKind kind, const shared::KeyParams& params, std::size_t count) {
  std::vector<Record> records;
  records.reserve(count);
  for (std::size_t i = 0; i < count; ++i) records.push_back(Make(kind, params));
  return records;
}

std::vector<Record> RecordGenerator::MixedBatch(const shared::KeyParams& params, std::size_t count) {
  std::vector<Record> records;
  records.reserve(count);
  for (std::size_t i = 0; i < count; ++i) records.push_back(Make(RecordKind(Bits() % 7u), params));
  return records;
}

KeyPathTrace TraceKeyPath(const Record& r, const shared::KeyParams& p) {
  const shared::RngCounter counter = shared::JitterCounter(p, r);
  const float u1 = shared::RandomFloat(counter, shared::kJitterDimensionU);
  const float u2 = shared::RandomFloat(counter, shared::kJitterDimensionV);
  const JitterSetup setup = Setup(r, p);
  KeyPathTrace t;
  t.jittered = shared::JitterInTangentPlane(glm::vec3(r.position), glm::vec3(r.tangent), glm::vec3(r.bitangent),
                                            setup.amplitude, u1, u2);
  t.path_length = shared::PathLength(r.position.w, t.jittered, glm::vec3(r.previous));
  float inverse = setup.inverse_size;
  if (p.lod_enabled != 0u) {
    inverse = shared::PowerOfTwo(-shared::LevelOfDetail(p.footprint_scale, t.path_length, p.level_min, p.level_max));
  }
  t.inverse_size = inverse;
  t.quotient = t.jittered * inverse;
  return t;
}

int UlpsToInteger(float x) {
  if (!std::isfinite(x)) return INT32_MAX;
  const float nearest = std::round(x);
  int ulps = 0;
  for (float y = x; y != nearest && ulps < 64; ++ulps) y = std::nextafter(y, nearest);
  return ulps;
}

int UlpsToPowerOfTwo(float x) {
  if (!(std::isfinite(x) && x > 0.0f)) return INT32_MAX;
  const int e = std::ilogb(x);
  const float below = std::ldexp(1.0f, e), above = std::ldexp(1.0f, e + 1);
  int ulps_down = 0, ulps_up = 0;
  for (float y = x; y != below && ulps_down < 64; ++ulps_down) y = std::nextafter(y, 0.0f);
  for (float y = x; y != above && ulps_up < 64; ++ulps_up) y = std::nextafter(y, INFINITY);
  return std::min(ulps_down, ulps_up);
}

}  // namespace hpsf::testing
