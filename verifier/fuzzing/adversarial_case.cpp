#include "verifier/fuzzing/adversarial_case.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "core/cell_interpolation.h"
#include "core/eviction.h"
#include "core/footprint.h"
#include "core/level_seed.h"
#include "core/shared/cell_interpolation.h"
#include "core/shared/key.h"
#include "core/shared/rng.h"
#include "core/temporal.h"
#include "verifier/generators/record_generators.h"

namespace hpsf {
namespace {

using testing::RecordGenerator;

constexpr double kFovY = 0.5;  // with height 1, the footprint scale the key-path family's records are solved for

// Keys chosen by cell: level of detail off, unit cells, no jitter, no normal bucket, so a record at the centre of
// a cell has that cell, and its slot0 and fingerprint are known before it is filtered.
FilterConfig CellKeyedConfig(RecordGenerator& g) {
  FilterConfig c;
  c.lod = false;
  c.cell_size = 1.0f;
  c.jitter_scale = 0.0f;
  c.normal = {NormalMode::kNone, 0};
  c.seed = g.Bits();
  return c;
}

KeyResult KeyOfCell(const shared::KeyParams& params, glm::ivec3 cell) {
  VertexSample v;
  v.position = glm::vec3(cell) + glm::vec3(0.5f);
  v.previous = v.position + glm::vec3(0.0f, 0.0f, -10.0f);
  return shared::ComputeKey(params, MakeVertexRecord(v));
}

glm::ivec3 RandomCell(RecordGenerator& g, int extent) {
  return {g.UniformInt(-extent, extent), g.UniformInt(-extent, extent), g.UniformInt(-extent, extent)};
}

// Cells along a random line of the grid, each with its key, until `visit` says it has enough (or 2^16 cells).
template <typename Visit>
void ScanCells(RecordGenerator& g, const FilterConfig& config, Visit visit) {
  const shared::KeyParams params = MakeKeyParams(config, 0.01f, 1);
  const glm::ivec3 start = RandomCell(g, 1 << 20);
  for (int x = 0; x < 1 << 16; ++x) {
    const glm::ivec3 cell = start + glm::ivec3(x, 0, 0);
    if (visit(KeyOfCell(params, cell), cell)) return;
  }
}

// Up to `count` distinct cells whose key satisfies `wanted`.
template <typename Wanted>
std::vector<glm::ivec3> SearchCells(RecordGenerator& g, const FilterConfig& config, std::size_t count, Wanted wanted) {
  std::vector<glm::ivec3> found;
  ScanCells(g, config, [&](const KeyResult& k, glm::ivec3 cell) {
    if (wanted(k)) found.push_back(cell);
    return found.size() >= count;
  });
  return found;
}

glm::vec3 Contribution(RecordGenerator& g) {
  glm::vec3 c(g.Uniform(0.0f, 4.0f), g.Uniform(0.0f, 4.0f), g.Uniform(0.0f, 4.0f));
  if (g.Bits() % 8u == 0u) c[g.UniformInt(0, 2)] = 0.0f;  // a zero channel, as a saturated albedo gives
  return c;
}

// Every record's contribution times `factor` (a rejected one stays rejected: NaN, infinite or negative).
RecordBatch Brightened(RecordBatch batch, float factor) {
  for (Record& r : batch.records) {
    for (int c = 0; c < 3; ++c) r.contribution[c] *= factor;
  }
  return batch;
}

VertexSample CellVertex(RecordGenerator& g, glm::ivec3 cell, std::uint32_t pixel) {
  VertexSample v;
  v.pixel = pixel;
  v.position = glm::vec3(cell) + glm::vec3(0.5f);
  v.previous = v.position + glm::vec3(0.0f, 0.0f, -10.0f);
  v.normal = glm::vec3(0.0f, 0.0f, (g.Bits() & 1u) ? 1.0f : -1.0f);
  v.contribution = Contribution(g);
  v.throughput = glm::vec3(g.Uniform(0.125f, 1.0f));
  v.radiance_before = glm::vec3(g.Uniform(0.0f, 0.5f));
  return v;
}

// One in sixteen records becomes one a table must never hold, or one it must leave alone: rejected inputs (NaN,
// infinite, negative), an unkeyable position (|q| >= 2^31) and a sample without a filter vertex.
Record Spoil(RecordGenerator& g, Record r) {
  if (g.Bits() % 16u != 0u) return r;
  const int channel = g.UniformInt(0, 2);
  switch (g.Bits() % 5u) {
    case 0:
      r.contribution[channel] = std::numeric_limits<float>::quiet_NaN();
      break;
    case 1:
      r.contribution[channel] = std::numeric_limits<float>::infinity();
      break;
    case 2:
      r.contribution[channel] = -g.Uniform(0.001f, 2.0f);
      break;
    case 3:
      r.position.x = 3e9f;
      r.previous.x = 3e9f;
      break;
    default:
      return MakeRecordWithoutVertex(r.path.x, 0u, glm::vec3(r.radiance_before));
  }
  return r;
}

// Records over the given cells: each cell once, in order (the searched cells come first, so a short batch keeps
// them), then in runs, each record repeating the previous one's cell with probability 1/2, so neighbours (one
// subgroup, one warp) often share a cell or race for one slot.
std::vector<Record> RecordsOverCells(RecordGenerator& g, const std::vector<glm::ivec3>& cells, std::uint32_t count) {
  std::vector<Record> records;
  std::size_t cell = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (i < cells.size()) {
      cell = i;
    } else if (g.Bits() & 1u) {
      cell = g.Bits() % cells.size();
    }
    records.push_back(Spoil(g, MakeVertexRecord(CellVertex(g, cells[cell], i))));
  }
  return records;
}

std::uint32_t PowerOfTwo(RecordGenerator& g, int low_log2, int high_log2) {
  return 1u << g.UniformInt(low_log2, high_log2);
}

std::uint32_t ProbeLimit(RecordGenerator& g, std::uint32_t capacity, std::uint32_t at_most) {
  return std::uint32_t(g.UniformInt(1, int(std::min(capacity, at_most))));
}

// A crowded tiny table: 1 to 64 slots and a handful of cells.
std::vector<glm::ivec3> Crowded(RecordGenerator& g, FilterConfig& c) {
  c.capacity = PowerOfTwo(g, 0, 6);
  c.probe_limit = ProbeLimit(g, c.capacity, 8);
  c.fingerprint_bits = std::array{8u, 16u, 32u}[g.Bits() % 3u];
  std::vector<glm::ivec3> cells(std::size_t(g.UniformInt(1, 12)));
  for (glm::ivec3& cell : cells) cell = RandomCell(g, 8);
  return cells;
}

// Keys whose fingerprint, reduced to 8..10 bits, is 0 before the fix that keeps it off the empty tag.
std::vector<glm::ivec3> ZeroFingerprint(RecordGenerator& g, FilterConfig& c) {
  c.capacity = PowerOfTwo(g, 2, 8);
  c.probe_limit = ProbeLimit(g, c.capacity, 8);
  c.fingerprint_bits = std::uint32_t(g.UniformInt(8, 10));
  const std::uint32_t bits = c.fingerprint_bits;
  std::vector<glm::ivec3> cells = SearchCells(g, c, std::size_t(g.UniformInt(1, 3)), [&](const KeyResult& k) {
    return (shared::FullFingerprint(k.words) >> (32u - bits)) == 0u;
  });
  for (int filler = g.UniformInt(0, 6); filler > 0; --filler) cells.push_back(RandomCell(g, 8));
  return cells;
}

// Distinct keys whose windows reach the last slot, so probing must wrap to slot 0.
std::vector<glm::ivec3> WrappingWindows(RecordGenerator& g, FilterConfig& c) {
  c.capacity = PowerOfTwo(g, 1, 8);
  c.probe_limit = std::max(2u, ProbeLimit(g, c.capacity, 8));
  c.fingerprint_bits = std::array{8u, 32u}[g.Bits() % 2u];
  std::vector<glm::ivec3> cells = SearchCells(g, c, std::size_t(g.UniformInt(2, 6)),
                                              [&](const KeyResult& k) { return k.slot0 + c.probe_limit > c.capacity; });
  for (int filler = g.UniformInt(0, 3); filler > 0; --filler) cells.push_back(RandomCell(g, 8));
  return cells;
}

// Pairs of distinct keys with the same slot0 and the same 8-bit fingerprint: aliases a table cannot tell apart.
std::vector<glm::ivec3> SharedFingerprint(RecordGenerator& g, FilterConfig& c) {
  c.capacity = PowerOfTwo(g, 2, 6);
  c.probe_limit = ProbeLimit(g, c.capacity, 4);
  c.fingerprint_bits = 8;
  std::map<std::pair<std::uint32_t, std::uint32_t>, glm::ivec3> first_of;
  std::vector<glm::ivec3> cells;
  const std::size_t pairs = std::size_t(g.UniformInt(1, 3));
  ScanCells(g, c, [&](const KeyResult& k, glm::ivec3 cell) {
    const auto [it, inserted] = first_of.try_emplace({k.slot0, k.fingerprint}, cell);
    if (!inserted) cells.insert(cells.end(), {it->second, cell});
    return cells.size() >= 2 * pairs;
  });
  for (int filler = g.UniformInt(0, 4); filler > 0; --filler) cells.push_back(RandomCell(g, 8));
  return cells;
}

// The key path's hard cases from the property-test generators (cell and level boundaries, far positions,
// signed-zero normals, no vertex) under any key configuration, in a crowded table.
std::vector<Record> KeyPath(RecordGenerator& g, FilterConfig& c, std::uint32_t count) {
  testing::KeyCase key_case = g.Case();
  const std::uint32_t seed = c.seed;
  c = key_case.config;
  c.seed = seed;
  c.frame = 0;
  c.capacity = PowerOfTwo(g, 0, 8);
  c.probe_limit = ProbeLimit(g, c.capacity, 16);
  const shared::KeyParams params = MakeKeyParams(c, FootprintScale(c.filter_width_px, kFovY, 1), count);
  std::vector<Record> records;
  for (Record& r : g.MixedBatch(params, count)) records.push_back(Spoil(g, r));
  return records;
}

// A few cells over 2 to 4 workgroups of the Vulkan accumulate. Layouts: aligned (every workgroup visits the same
// cells in the same order, so two worker threads claim and join one cell at the same moment), strided (record i's
// cell is i mod the cell count) and runs (a cell's records in runs that cross the workgroups' boundaries).
std::vector<Record> Spread(RecordGenerator& g, FilterConfig& c) {
  c.capacity = PowerOfTwo(g, 8, 12);
  c.probe_limit = ProbeLimit(g, c.capacity, 16);
  c.fingerprint_bits = 32;
  const std::uint32_t workgroups = std::uint32_t(g.UniformInt(2, 4));
  const std::uint32_t count = (workgroups - 1) * kAccumulateRecordsPerWorkgroup +
                              std::uint32_t(g.UniformInt(1, int(kAccumulateRecordsPerWorkgroup)));
  std::vector<glm::ivec3> cells(std::size_t(g.UniformInt(1, int(c.capacity / 4))));
  for (glm::ivec3& cell : cells) cell = RandomCell(g, 64);
  std::vector<std::uint32_t> order(kAccumulateRecordsPerWorkgroup);  // the aligned layout's cell per offset
  for (std::uint32_t& o : order) o = g.Bits() % std::uint32_t(cells.size());
  const std::uint32_t layout = g.Bits() % 3u;
  std::vector<Record> records;
  std::uint32_t cell = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (layout == 0) {
      cell = order[i % kAccumulateRecordsPerWorkgroup];
    } else if (layout == 1) {
      cell = i % std::uint32_t(cells.size());
    } else if (g.Bits() % 64u == 0u) {
      cell = g.Bits() % std::uint32_t(cells.size());
    }
    records.push_back(Spoil(g, MakeVertexRecord(CellVertex(g, cells[cell], i))));
  }
  return records;
}

// A later frame of a sequence: each record of the first frame again with probability 3/4 (a cell joined, not
// claimed), then up to a quarter as many records over fresh cells (new claims, eviction pressure). Pixels follow
// the records' order.
RecordBatch LaterFrame(RecordGenerator& g, const RecordBatch& first, std::uint32_t number) {
  RecordBatch frame = first;
  frame.records.clear();
  for (const Record& r : first.records) {
    if (g.Bits() % 4u != 0u) frame.records.push_back(r);
  }
  const int fresh = g.UniformInt(0, int(first.records.size() / 4));
  for (int n = 0; n < fresh; ++n) {
    frame.records.push_back(MakeVertexRecord(CellVertex(g, RandomCell(g, 8), 0)));
  }
  if (frame.records.empty()) frame.records.push_back(first.records.front());
  for (std::uint32_t i = 0; i < frame.records.size(); ++i) frame.records[i].path.x = i;
  frame.width = std::uint32_t(frame.records.size());
  frame.frame = number;
  return frame;
}

// The table's life over a sequence: a policy and a temporal mode of every kind (priority reserves the tag
// 0xFFFFFFFF, so it keeps fingerprints of 31 bits or fewer).
void DrawSequenceConfig(RecordGenerator& g, FilterConfig& c) {
  const char* const evictions[] = {"none", "strict", "stale:1", "stale:2", "stale:3", "priority"};
  const char* const temporals[] = {"integrate", "ema:0.5", "ema:0.25:8", "adaptive"};
  c.eviction = ParseEviction(evictions[g.Bits() % 6u]);
  c.temporal = ParseTemporal(temporals[g.Bits() % 4u]);
  if (c.eviction.by_priority() && c.key_identity == KeyIdentity::kFingerprint && c.fingerprint_bits > 24) {
    c.fingerprint_bits = 24;
  }
}

}  // namespace

std::vector<RecordBatch> AdversarialCase::Frames() const {
  std::vector<RecordBatch> frames = {batch};
  frames.insert(frames.end(), later.begin(), later.end());
  return frames;
}

std::size_t AdversarialCase::Records() const {
  std::size_t records = batch.records.size();
  for (const RecordBatch& frame : later) records += frame.records.size();
  return records;
}

const char* ToString(AdversarialFamily family) {
  switch (family) {
    case AdversarialFamily::kCrowded:
      return "crowded";
    case AdversarialFamily::kZeroFingerprint:
      return "zero-fingerprint";
    case AdversarialFamily::kWrappingWindows:
      return "wrapping-windows";
    case AdversarialFamily::kSharedFingerprint:
      return "shared-fingerprint";
    case AdversarialFamily::kKeyPath:
      return "key-path";
    case AdversarialFamily::kSpread:
      return "spread";
  }
  return "?";
}

std::string AdversarialCase::ToString() const {
  std::string s = std::string(hpsf::ToString(family)).append(": ").append(std::to_string(Records()));
  s.append(" records");
  if (!later.empty()) s.append(" in ").append(std::to_string(later.size() + 1)).append(" frames");
  s.append(", ").append(config.ToString());
  if (emulator.mode == simt::Mode::kFaithful) {
    s.append(", faithful warp ")
        .append(std::to_string(emulator.warp_size))
        .append(" schedule ")
        .append(emulator.schedule);
    if (emulator.spurious_cas > 0.0) s.append(" spurious-cas ").append(std::to_string(emulator.spurious_cas));
  } else {
    s.append(", fast");
  }
  return s;
}

AdversarialCase MakeAdversarialCase(std::uint32_t seed, std::uint64_t run, const AdversarialOptions& options) {
  RecordGenerator g(shared::RandomBits({seed, std::uint32_t(run), std::uint32_t(run >> 32), 0u, 0u}, 0xADF0u));
  AdversarialCase a;
  a.family =
      AdversarialFamily(g.Bits() % std::uint32_t(options.spread ? kAdversarialFamilies : kAdversarialFamilies - 1));
  a.config = CellKeyedConfig(g);
  const Accumulation accumulation = g.Bits() % 4u == 0u ? Accumulation::kFloat32 : Accumulation::kFixed64;
  const std::uint32_t count = std::uint32_t(g.UniformInt(2, int(std::max(2u, options.max_records))));
  std::vector<glm::ivec3> cells;
  switch (a.family) {
    case AdversarialFamily::kCrowded:
      cells = Crowded(g, a.config);
      break;
    case AdversarialFamily::kZeroFingerprint:
      cells = ZeroFingerprint(g, a.config);
      break;
    case AdversarialFamily::kWrappingWindows:
      cells = WrappingWindows(g, a.config);
      break;
    case AdversarialFamily::kSharedFingerprint:
      cells = SharedFingerprint(g, a.config);
      break;
    case AdversarialFamily::kKeyPath:
      a.batch.records = KeyPath(g, a.config, count);
      break;
    case AdversarialFamily::kSpread:
      a.batch.records = Spread(g, a.config);
      break;
  }
  // After the family, whose key-path configuration replaces the whole config: a user's shader handles its mode only.
  a.config.accumulation = options.accumulation ? *options.accumulation : accumulation;
  // The probing scheme and the weak CAS from a generator of their own, added after the others, so that every draw of
  // a seed's cases made before them stays what it was.
  RecordGenerator late_draws(shared::RandomBits({seed, std::uint32_t(run), std::uint32_t(run >> 32), 1u, 0u}, 0xADF1u));
  const std::uint32_t draw = late_draws.Bits() % 4u;
  a.config.probing = options.probing ? *options.probing
                     : draw == 2u    ? ProbeKind::kBucket
                     : draw == 3u    ? ProbeKind::kBucketWindow
                                     : ProbeKind::kLinear;
  if (a.config.probing == ProbeKind::kBucket) a.config.probe_limit = std::bit_floor(a.config.probe_limit);
  // A case in four of the families whose aim is not a fingerprint's stores full keys (core/key_identity.h), where a
  // normal bucket fits one, from a generator of its own too. Half of the crowded ones move their cells into one
  // column (the first cell's x and y), where every key has the same low word, so that a slot of another cell of the
  // column lies in a record's window.
  RecordGenerator identity_draws(
      shared::RandomBits({seed, std::uint32_t(run), std::uint32_t(run >> 32), 2u, 0u}, 0xADF2u));
  const bool normal_fits = a.config.normal.mode != NormalMode::kOctahedral || a.config.normal.octahedral_bits <= 1;
  const bool fingerprint_aim = a.family == AdversarialFamily::kZeroFingerprint ||
                               a.family == AdversarialFamily::kSharedFingerprint ||
                               a.family == AdversarialFamily::kWrappingWindows;
  if (!options.fingerprints) {
    a.config.key_identity = KeyIdentity::kFull;
    a.config.fingerprint_bits = 32;
    if (!normal_fits) a.config.normal = NormalKey{NormalMode::kSign, 0};
  } else if (identity_draws.Bits() % 4u == 0u && normal_fits && !fingerprint_aim && options.full_keys) {
    a.config.key_identity = KeyIdentity::kFull;
    a.config.fingerprint_bits = 32;
    if (a.family == AdversarialFamily::kCrowded && identity_draws.Bits() % 2u == 0u) {
      for (glm::ivec3& cell : cells) cell = {cells.front().x, cells.front().y, cell.z};
    }
  }
  if (a.family != AdversarialFamily::kKeyPath && a.family != AdversarialFamily::kSpread) {
    if (cells.empty()) cells.push_back(RandomCell(g, 8));  // a search that found nothing still gives a batch
    a.batch.records = RecordsOverCells(g, cells, count);
  }
  a.batch.width = std::uint32_t(a.batch.records.size());
  a.batch.height = 1;
  a.batch.samples_per_pixel = 1;
  a.batch.fov_y_radians = kFovY;

  // The emulator: mostly faithful warps under a drawn schedule, where races replay from the seed.
  if (options.allow_fast_mode && g.Bits() % 4u == 0u) {
    a.emulator.mode = simt::Mode::kFast;
  } else {
    a.emulator.mode = simt::Mode::kFaithful;
    a.emulator.warp_size = std::array{8u, 32u, 64u}[g.Bits() % 3u];
    const std::uint32_t schedule_seed = g.Bits() % 100000u;
    switch (g.Bits() % 3u) {
      case 0:
        a.emulator.schedule = "round-robin";
        break;
      case 1:
        a.emulator.schedule = "random:" + std::to_string(schedule_seed);
        break;
      default:
        a.emulator.schedule = "pct:" + std::to_string(schedule_seed) + ":" + std::to_string(g.UniformInt(1, 4));
        break;
    }
    // Half the faithful cases fail a quarter of their weak compare-and-swaps spuriously.
    if (late_draws.Bits() % 2u == 0u) a.emulator.spurious_cas = 0.25;
  }
  // Rounding: a small F of the case's own, where truncation and rounding differ.
  if (a.config.accumulation == Accumulation::kFixed64 && g.Bits() % 4u == 0u) {
    a.config.fixed_point_bits = g.UniformInt(-2, 9);
  }
  // Frame state: a sequence through one table.
  if (g.Bits() % 4u == 0u) {
    DrawSequenceConfig(g, a.config);
    const int frames = g.UniformInt(2, 6);
    for (int k = 1; k < frames; ++k) a.later.push_back(LaterFrame(g, a.batch, std::uint32_t(k)));
    a.config.frames = std::uint32_t(frames);
    // Half the sequences step their passes over an occupied list (core/compaction.h). A later frame in eight sees
    // only sky (its records lose their vertex): nothing is touched, and a policy may evict every cell.
    if (late_draws.Bits() % 2u == 0u) a.config.compaction = Compaction::kOccupiedList;
    for (RecordBatch& frame : a.later) {
      if (late_draws.Bits() % 8u != 0u) continue;
      for (Record& r : frame.records) r.path.z &= ~shared::kRecordHasVertex;
    }
  }
  // packed-decimal sums (core/shared/packed_sums.h) in a sixth of the cases, from a generator of their own.
  RecordGenerator sums_draws(shared::RandomBits({seed, std::uint32_t(run), std::uint32_t(run >> 32), 3u, 0u}, 0xADF3u));
  if (!options.accumulation && sums_draws.Bits() % 6u == 0u && options.packed_sums) {
    a.config.accumulation = Accumulation::kPackedDecimal;
  }
  if (a.config.accumulation == Accumulation::kPackedDecimal) {
    a.config.fixed_point_bits.reset();
    // Half of them bright sequences, so the settle's halving runs. A record's channel below B / (1000 n), for the n
    // records of the largest frame, keeps a cell's adds of one frame below B, so no word wraps: a settled sum is below
    // 2^31, and with B = 2^31 a frame's adds keep it below 2^32. A blend may exceed the integrated sum by one average
    // (core/shared/temporal_blend.h), so a blending case takes B = 2^30. A cell that gathers most of a frame's
    // records still reaches 2^31 within a few frames and halves.
    if (sums_draws.Bits() % 2u == 0u) {
      if (a.later.empty()) {  // a sequence: a cell reaches 2^31 over frames
        DrawSequenceConfig(sums_draws, a.config);
        const int frames = sums_draws.UniformInt(3, 6);
        for (int k = 1; k < frames; ++k) a.later.push_back(LaterFrame(sums_draws, a.batch, std::uint32_t(k)));
        a.config.frames = std::uint32_t(frames);
      }
      std::size_t most = a.batch.records.size();
      for (const RecordBatch& frame : a.later) most = std::max(most, frame.records.size());
      const double bound = a.config.temporal.blends() ? 0x1p30 : 0x1p31;
      // Contribution() draws below 4; 0.99 leaves room for each add's rounding to an integer.
      const float bright = float(bound / (1000.0 * 4.0 * double(std::max<std::size_t>(most, 1))) * 0.99);
      a.batch = Brightened(a.batch, bright);
      for (RecordBatch& frame : a.later) frame = Brightened(frame, bright);
    }
  }
  // Multi-level accumulation (core/shared/levels.h) in a quarter of the cases whose passes know the levels, from a
  // generator of its own, so a seed's cases are otherwise what they were.
  RecordGenerator level_draws(
      shared::RandomBits({seed, std::uint32_t(run), std::uint32_t(run >> 32), 4u, 0u}, 0xADF4u));
  if (options.levels && level_draws.Bits() % 4u == 0u) {
    a.config.levels = 2u + level_draws.Bits() % 2u;
    a.config.min_count = 1u + level_draws.Bits() % 4u;
  }
  // The neighbourhood search (core/shared/neighbour_search.h) in a quarter of the cases, with a threshold of 2 to 4.
  if (options.search && level_draws.Bits() % 4u == 0u) {
    a.config.neighbour_search = true;
    a.config.min_count = std::max(a.config.min_count, 2u + level_draws.Bits() % 3u);
  }
  // Resolution changes (core/level_seed.h) in half the sequences keyed with level of detail (the key-path family's):
  // a later frame sees half its records from twice or half as far, so they key a cell a level coarser or finer,
  // which starts seeded from the cells of the frame before.
  if (options.level_change && a.config.lod && !a.later.empty() && level_draws.Bits() % 2u == 0u) {
    const std::uint32_t shift = level_draws.Bits() % 3u;
    a.config.level_seed = ParseLevelSeed(shift == 0u ? "seed" : "seed:" + std::to_string(shift));
    for (RecordBatch& frame : a.later) {
      for (Record& r : frame.records) {
        if (level_draws.Bits() % 2u != 0u) continue;
        const float scale = level_draws.Bits() % 2u == 0u ? 2.0f : 0.5f;
        const glm::vec3 x(r.position);
        r.previous = glm::vec4(x + (glm::vec3(r.previous) - x) * scale, 0.0f);
        r.position.w *= scale;  // d_prefix, the path length before x_prev
      }
    }
  }
  // Several filtered bounces (core/transport.h), from a generator of their own: each record of each frame scatters
  // to the vertex of a record of its frame drawn at random, with a transport weight below 1/2 per channel (so the
  // transported light stays within twice the frame's, inside F's headroom for the sequence); one in eight scatters
  // nowhere.
  RecordGenerator transport_draws(
      shared::RandomBits({seed, std::uint32_t(run), std::uint32_t(run >> 32), 5u, 0u}, 0xADF5u));
  if (options.transport && !a.later.empty() && a.config.accumulation != Accumulation::kPackedDecimal &&
      transport_draws.Bits() % 2u == 0u) {
    a.config.transport = true;
    std::vector<RecordBatch*> frames = {&a.batch};
    for (RecordBatch& frame : a.later) frames.push_back(&frame);
    for (RecordBatch* frame : frames) {
      frame->scattered.clear();
      const std::size_t n = frame->records.size();
      for (std::size_t i = 0; i < n; ++i) {
        Record s = frame->records[transport_draws.Bits() % n];
        if (transport_draws.Bits() % 8u == 0u) s.path.z &= ~shared::kRecordHasVertex;
        s.throughput = glm::vec4(transport_draws.Uniform(0.0f, 0.5f), transport_draws.Uniform(0.0f, 0.5f),
                                 transport_draws.Uniform(0.0f, 0.5f), 0.0f);
        frame->scattered.push_back(s);
      }
    }
  }
  // Second moments in a quarter of the cases that can keep them (not packed-decimal's sums, no level seeding), from a
  // generator of their own.
  RecordGenerator moment_draws(
      shared::RandomBits({seed, std::uint32_t(run), std::uint32_t(run >> 32), 6u, 0u}, 0xADF6u));
  if (options.second_moments && a.config.accumulation != Accumulation::kPackedDecimal && !a.config.level_seed.enabled &&
      moment_draws.Bits() % 4u == 0u) {
    a.config.second_moments = true;
    // Half of them interpolate (not with the search, whose stencil the rule does not weigh), by a rule whose
    // thresholds span the variances of cells of the drawn contributions: V0 from 1e-6 to 1, V1 up to 100 times it.
    if (options.interpolation && !a.config.neighbour_search && moment_draws.Bits() % 2u == 0u) {
      CellInterpolation& rule = a.config.interpolation;
      rule.function = moment_draws.Bits() % 2u == 0u ? shared::kInterpolationStep : shared::kInterpolationSmooth;
      rule.v0 = std::pow(10.0, double(moment_draws.Uniform(-6.0f, 0.0f)));
      rule.v1 = std::min(rule.v0 * std::pow(10.0, double(moment_draws.Uniform(0.3f, 2.0f))), rule.v0 + 7.5);
      // Half of them blend own lights other than the records' contributions, as a path graph's cut paths carry
      // (RecordBatch::own_light): each channel drawn in [0, 2], finite whatever the record holds.
      if (moment_draws.Bits() % 2u == 0u) {
        std::vector<RecordBatch*> frames = {&a.batch};
        for (RecordBatch& frame : a.later) frames.push_back(&frame);
        for (RecordBatch* frame : frames) {
          frame->own_light.clear();
          for (std::size_t i = 0; i < frame->records.size(); ++i) {
            const float r = moment_draws.Uniform(0.0f, 2.0f), g = moment_draws.Uniform(0.0f, 2.0f);
            frame->own_light.push_back(glm::vec4(r, g, moment_draws.Uniform(0.0f, 2.0f), 0.0f));
          }
        }
      }
    }
    // Half of the adaptive sequences judge their change against the cells' variance.
    if (a.config.temporal.mode == TemporalMode::kAdaptive && moment_draws.Bits() % 2u == 0u) {
      a.config.temporal = ParseTemporal("adaptive-variance");
    }
  }
  a.config.Validate();
  return a;
}

}  // namespace hpsf
