#include "tools/fuzz/fuzz_batch.h"

#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "core/key_batch.h"

namespace hpsf {
namespace {

// A constructed cell is searched along x; at 8 fingerprint bits or 256 slots a match is a few hundred keys away.
constexpr int kCellSearchLimit = 2048;
constexpr int kMaxCells = 8;
// Far enough out that |x / cell| >= 2^31: the record is unkeyable.
constexpr float kUnkeyableCoordinate = 4.5e9f;

// 2.5e6 is past 2^31 at packed-decimal's scale 1000: one record halves a cell, two wrap its 32-bit sum.
const std::array<float, 8> kContributions = {0.5f, 1.0f, 0.0f, 1e-3f, 3.25f, 2.5e6f, 0x1p-20f, 65504.0f};
const std::array<float, 4> kOffsetsInCell = {0.5f, 0.0f, 0.25f, 0.99951171875f};  // 0: on the cell's lower boundary
const std::array<glm::vec3, 4> kNormals = {glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f, 0.0f, -1.0f),
                                           glm::vec3(-0.0f, 1.0f, 0.0f), glm::vec3(1.0f, -0.0f, 0.0f)};

enum class CellChoice {
  kNear,
  kSameFingerprint,
  kSameSlot0,
  kLastSlot,
  kFingerprintOne,
  kAnywhere,
  kMaxValue = kAnywhere
};
enum class RecordKind { kVertex, kNoVertex, kUnkeyable, kNonFinite, kNegative, kMaxValue = kNegative };

VertexSample VertexIn(glm::ivec3 cell, glm::vec3 offset, glm::vec3 normal) {
  VertexSample v;
  v.position = glm::vec3(cell) + offset;
  v.normal = normal;
  v.previous = v.position + glm::vec3(0.0f, 0.0f, -1.0f);
  v.contribution = glm::vec3(0.5f);
  v.throughput = glm::vec3(0.5f);
  return v;
}

KeyResult KeyOfCell(const FilterConfig& config, glm::ivec3 cell) {
  return shared::ComputeKey(MakeKeyParams(config, 0.01f, 1),
                            MakeVertexRecord(VertexIn(cell, glm::vec3(0.5f), kNormals[0])));
}

// The first cell along x after `from` whose key satisfies `wanted`, or `from` itself if none is near.
glm::ivec3 SearchCell(const FilterConfig& config, glm::ivec3 from,
                      const std::function<bool(const KeyResult&)>& wanted) {
  for (int step = 1; step <= kCellSearchLimit; ++step) {
    const glm::ivec3 cell = from + glm::ivec3(step, 0, 0);
    if (wanted(KeyOfCell(config, cell))) return cell;
  }
  return from;
}

FilterConfig DecodeConfig(FuzzedDataProvider& input, bool packed_sums, bool& constructed_keys) {
  FilterConfig c;
  c.capacity = 1u << input.ConsumeIntegralInRange<std::uint32_t>(0, kFuzzMaxCapacityLog2);
  c.probe_limit = input.ConsumeIntegralInRange<std::uint32_t>(1, c.capacity);
  c.fingerprint_bits = input.ConsumeIntegralInRange<std::uint32_t>(8, 32);
  // One byte, whose low bit picks float32 as ConsumeBool did, so inputs saved before packed sums decode as they did.
  const int sums = input.ConsumeIntegralInRange<int>(0, 3);
  c.accumulation = sums % 2 == 1              ? Accumulation::kFloat32
                   : sums == 2 && packed_sums ? Accumulation::kPackedDecimal
                                              : Accumulation::kFixed64;
  c.seed = input.ConsumeIntegral<std::uint32_t>();
  // One input in four keeps second moments (core/shared/second_moment.h), where the sums can: decided by the seed
  // word, so that inputs saved before decode as they did.
  c.second_moments = c.accumulation != Accumulation::kPackedDecimal && c.seed % 4u == 0u;
  const std::uint8_t normal = input.ConsumeIntegralInRange<std::uint8_t>(0, 3);
  c.normal = normal == 0   ? NormalKey{NormalMode::kNone, 0}
             : normal == 1 ? NormalKey{NormalMode::kSign, 0}
                           : NormalKey{NormalMode::kOctahedral, normal};
  c.normal_in_index = input.ConsumeBool();
  // One input in eight keys by the level of detail with jitter, as a render does; the others by unit cells.
  constructed_keys = input.ConsumeIntegralInRange<int>(0, 7) != 0;
  c.lod = !constructed_keys;
  c.jitter_scale = constructed_keys ? 0.0f : 1.0f;
  c.cell_size = 1.0f;
  // The probing scheme, a bucket's size rounded down to a power of two.
  const std::uint8_t scheme = input.ConsumeIntegralInRange<std::uint8_t>(0, 2);
  c.probing = scheme == 0 ? ProbeKind::kLinear : scheme == 1 ? ProbeKind::kBucket : ProbeKind::kBucketWindow;
  if (c.probing == ProbeKind::kBucket) c.probe_limit = std::bit_floor(c.probe_limit);
  return c;
}

EmulatorOptions DecodeFaithful(FuzzedDataProvider& input) {
  static constexpr std::array<std::uint32_t, 6> kWarpSizes = {8, 1, 2, 3, 32, 64};
  EmulatorOptions o;
  o.mode = simt::Mode::kFaithful;
  o.warp_size = kWarpSizes[input.ConsumeIntegralInRange<std::size_t>(0, kWarpSizes.size() - 1)];
  const std::uint32_t seed = input.ConsumeIntegral<std::uint16_t>();
  switch (input.ConsumeIntegralInRange<int>(0, 2)) {
    case 0:
      o.schedule = "random:" + std::to_string(seed);
      break;
    case 1:
      o.schedule = "pct:" + std::to_string(seed) + ":" + std::to_string(input.ConsumeIntegralInRange<int>(1, 3));
      break;
    default:
      o.schedule = "round-robin";
      break;
  }
  return o;
}

std::vector<glm::ivec3> DecodeCells(FuzzedDataProvider& input, const FilterConfig& config, bool constructed_keys) {
  const glm::ivec3 base(input.ConsumeIntegral<std::int16_t>(), input.ConsumeIntegral<std::int16_t>(),
                        input.ConsumeIntegral<std::int16_t>());
  std::vector<glm::ivec3> cells = {base};
  const int count = input.ConsumeIntegralInRange<int>(1, kMaxCells);
  const KeyResult first = KeyOfCell(config, base);
  while (int(cells.size()) < count) {
    const glm::ivec3 previous = cells.back();
    CellChoice choice = input.ConsumeEnum<CellChoice>();
    if (!constructed_keys && choice != CellChoice::kAnywhere) choice = CellChoice::kNear;
    switch (choice) {
      case CellChoice::kNear: {
        const int dx = input.ConsumeIntegralInRange<int>(-2, 2), dy = input.ConsumeIntegralInRange<int>(-2, 2);
        cells.push_back(base + glm::ivec3(dx, dy, input.ConsumeIntegralInRange<int>(-2, 2)));
        break;
      }
      case CellChoice::kSameFingerprint:
        cells.push_back(
            SearchCell(config, previous, [&](const KeyResult& k) { return k.fingerprint == first.fingerprint; }));
        break;
      case CellChoice::kSameSlot0:
        cells.push_back(SearchCell(config, previous, [&](const KeyResult& k) { return k.slot0 == first.slot0; }));
        break;
      case CellChoice::kLastSlot:
        cells.push_back(
            SearchCell(config, previous, [&](const KeyResult& k) { return k.slot0 == config.capacity - 1; }));
        break;
      case CellChoice::kFingerprintOne:  // the reduced fingerprint was 0 or 1: where the empty-tag fix acts
        cells.push_back(SearchCell(config, previous, [&](const KeyResult& k) { return k.fingerprint == 1u; }));
        break;
      case CellChoice::kAnywhere: {
        constexpr int kRange = 1 << 22;  // positions stay exact in float
        const int x = input.ConsumeIntegralInRange<int>(-kRange, kRange),
                  y = input.ConsumeIntegralInRange<int>(-kRange, kRange);
        cells.emplace_back(x, y, input.ConsumeIntegralInRange<int>(-kRange, kRange));
        break;
      }
    }
  }
  return cells;
}

Record DecodeRecord(FuzzedDataProvider& input, const std::vector<glm::ivec3>& cells, std::uint32_t pixel,
                    std::uint32_t sample) {
  const RecordKind kind =
      input.ConsumeIntegralInRange<int>(0, 9) < 6 ? RecordKind::kVertex : input.ConsumeEnum<RecordKind>();
  const glm::vec3 radiance_before(input.ConsumeIntegralInRange<int>(0, 3) * 0.25f);
  if (kind == RecordKind::kNoVertex) return MakeRecordWithoutVertex(pixel, sample, radiance_before);
  const glm::ivec3 cell = cells[input.ConsumeIntegralInRange<std::size_t>(0, cells.size() - 1)];
  glm::vec3 offset;
  for (int axis = 0; axis < 3; ++axis)
    offset[axis] = kOffsetsInCell[input.ConsumeIntegralInRange<std::size_t>(0, kOffsetsInCell.size() - 1)];
  VertexSample v = VertexIn(cell, offset, kNormals[input.ConsumeIntegralInRange<std::size_t>(0, kNormals.size() - 1)]);
  v.pixel = pixel;
  v.sample = sample;
  v.radiance_before = radiance_before;
  for (int channel = 0; channel < 3; ++channel) {
    v.contribution[channel] = kContributions[input.ConsumeIntegralInRange<std::size_t>(0, kContributions.size() - 1)];
  }
  v.throughput = glm::vec3(input.ConsumeBool() ? 1.0f : 0.5f);
  if (kind == RecordKind::kUnkeyable) v.position.x = v.previous.x = kUnkeyableCoordinate;
  if (kind == RecordKind::kNonFinite) {
    const float bad =
        input.ConsumeBool() ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
    (input.ConsumeBool() ? v.contribution : v.throughput)[input.ConsumeIntegralInRange<int>(0, 2)] = bad;
  }
  if (kind == RecordKind::kNegative) {
    const float bad = input.ConsumeBool() ? -0.0f : -1.0f;
    if (input.ConsumeBool()) {
      v.d_prefix = bad;
    } else {
      v.contribution[input.ConsumeIntegralInRange<int>(0, 2)] = bad;
    }
  }
  return MakeVertexRecord(v);
}

}  // namespace

FuzzCase DecodeFuzzCase(FuzzedDataProvider& input, bool packed_sums) {
  FuzzCase c;
  bool constructed_keys = true;
  c.config = DecodeConfig(input, packed_sums, constructed_keys);
  c.faithful = DecodeFaithful(input);
  c.fast.mode = simt::Mode::kFast;
  c.fast.threads = 2;
  const std::vector<glm::ivec3> cells = DecodeCells(input, c.config, constructed_keys);

  RecordBatch& b = c.batch;
  b.samples_per_pixel = 1u << input.ConsumeIntegralInRange<int>(0, 2);
  b.width = input.ConsumeIntegralInRange<std::uint32_t>(1, kFuzzMaxRecords / b.samples_per_pixel);
  b.height = 1;
  b.fov_y_radians = 0.5;
  for (std::uint32_t pixel = 0; pixel < b.width; ++pixel) {
    for (std::uint32_t sample = 0; sample < b.samples_per_pixel; ++sample)
      b.records.push_back(DecodeRecord(input, cells, pixel, sample));
  }
  return c;
}

std::string FuzzCase::ToString() const {
  std::string s = "config: " + config.ToString() + "\nfaithful: warp size " + std::to_string(faithful.warp_size) +
                  ", schedule " + faithful.schedule + "\nbatch: " + std::to_string(batch.width) + "x" +
                  std::to_string(batch.height) + " at " + std::to_string(batch.samples_per_pixel) + " spp\n";
  for (const Record& r : batch.records) s.append(hpsf::ToString(r)).append("\n");
  return s;
}

}  // namespace hpsf
