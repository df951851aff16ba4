#include "core/hashcache_check.h"

#include <optional>
#include <string>

#include "core/format.h"
#include "core/hashcache_update.h"
#include "core/shared/fixed_point.h"
#include "core/shared/hashcache_cell.h"

namespace hpsf {
namespace {

std::string Text(std::uint64_t word) { return std::to_string(word); }
std::string Text(std::uint32_t word) { return std::to_string(word); }
std::string Text(float value) { return FormatFloatBits(value); }

// Each entry where two arrays of a level differ.
template <typename T>
void CompareArray(const char* name, std::size_t per_slot, const HashCacheLevel& expected, const std::vector<T>& want,
                  const std::vector<T>& got, std::vector<std::string>& problems) {
  if (want.size() != got.size()) {
    problems.push_back("level " + std::to_string(expected.level) + ": " + name + " has " + std::to_string(got.size()) +
                       " entries, not " + std::to_string(want.size()));
    return;
  }
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (want[i] == got[i]) continue;
    const std::size_t slot = i / per_slot;
    problems.push_back("level " + std::to_string(expected.level) + ", slot " + std::to_string(slot) + " (cell " +
                       std::to_string(expected.map.slots[slot]) + "): " + name + "[" + std::to_string(i % per_slot) +
                       "] is " + Text(got[i]) + ", not " + Text(want[i]));
  }
}

}  // namespace

std::vector<std::string> CheckHashCacheFrame(const HashCache& before, const HashCache& after,
                                             std::span<const HashCacheSample> samples) {
  std::vector<std::string> problems;
  if (after.levels.size() != before.levels.size() || after.accumulation != before.accumulation ||
      after.fixed_point_bits != before.fixed_point_bits) {
    return {"the cache's levels or accumulation changed in the update"};
  }
  std::vector<std::vector<std::uint32_t>> claims;
  for (std::size_t l = 0; l < after.levels.size(); ++l) {
    if (after.levels[l].map.slots != before.levels[l].map.slots) {
      problems.push_back("level " + std::to_string(l) + ": the map changed in the update");
    }
    claims.push_back(after.levels[l].data.front);
  }
  if (!problems.empty()) return problems;
  HashCache expected = before;
  const HashCacheUpdateReport report = UpdateHashCache(expected, samples, &claims);
  problems = report.problems;
  for (std::size_t l = 0; l < after.levels.size(); ++l) {
    const HashCacheData& want = expected.levels[l].data;
    const HashCacheData& got = after.levels[l].data;
    CompareArray("front", 1, expected.levels[l], want.front, got.front, problems);
    CompareArray("fixed sum", 6, expected.levels[l], want.fixed_sums, got.fixed_sums, problems);
    CompareArray("float sum", 6, expected.levels[l], want.float_sums, got.float_sums, problems);
    CompareArray("count", 2, expected.levels[l], want.counts, got.counts, problems);
    CompareArray("wiped", 1, expected.levels[l], want.wiped, got.wiped, problems);
  }
  return problems;
}

std::vector<std::string> CheckHashCacheSums(const HashCache& cache, std::span<const HashCacheSample> samples) {
  std::vector<std::string> problems;
  if (cache.accumulation != Accumulation::kFixed64) return {"the sums are checked for fixed64 only"};
  // want[l]: per slot, six sums and two counts.
  std::vector<std::vector<std::uint64_t>> sums, counts;
  const float scale = SumScale(cache.accumulation, cache.fixed_point_bits);
  for (const HashCacheLevel& level : cache.levels) {
    sums.emplace_back(level.data.fixed_sums.size(), 0);
    counts.emplace_back(level.data.counts.size(), 0);
  }
  const HashCacheLevel& finest = cache.levels[0];
  for (const HashCacheSample& s : samples) {
    const glm::ivec3 cell = shared::PointCell(cache.grid, s.position);
    if (cell.x < 0) continue;
    const std::optional<std::uint32_t> slot =
        finest.map.Find(shared::CuckooKey(cell.x, cell.y, cell.z, finest.cells_log2));
    if (!slot) continue;
    const std::size_t side = shared::FacesFront(shared::FrontWord(s.normal), finest.data.front[*slot]) ? 0 : 1;
    for (int c = 0; c < 3; ++c)
      sums[0][6 * *slot + 3 * side + c] += shared::ToFixedPoint(shared::Flush(s.light[c]), scale);
    counts[0][2 * *slot + side] += 1;
  }
  for (std::size_t l = 1; l < cache.levels.size() && cache.update == HashCacheUpdateRule::kAtomics; ++l) {
    const HashCacheLevel& level = cache.levels[l];
    for (const HashCacheSample& s : samples) {
      const glm::ivec3 cell = shared::PointCell(cache.grid, s.position);
      if (cell.x < 0) continue;
      const glm::ivec3 at = cell >> int(l);
      const std::optional<std::uint32_t> slot = level.map.Find(shared::CuckooKey(at.x, at.y, at.z, level.cells_log2));
      if (!slot) continue;
      const std::size_t side = shared::FacesFront(shared::FrontWord(s.normal), level.data.front[*slot]) ? 0 : 1;
      for (int c = 0; c < 3; ++c) {
        sums[l][6 * *slot + 3 * side + c] += shared::ToFixedPoint(shared::Flush(s.light[c]), scale);
      }
      counts[l][2 * *slot + side] += 1;
    }
  }
  for (std::size_t l = 1; l < cache.levels.size() && cache.update == HashCacheUpdateRule::kSortAndReduce; ++l) {
    const HashCacheLevel& child = cache.levels[l - 1];
    const HashCacheLevel& parent = cache.levels[l];
    for (std::size_t c = 0; c < child.map.slots.size(); ++c) {
      if (child.map.slots[c] == shared::kCuckooEmpty) continue;
      const std::uint32_t front = child.data.front[c];
      if (front == shared::kFrontUnclaimed) continue;
      const std::optional<std::uint32_t> p = parent.map.Find(shared::ParentKey(child.map.slots[c], child.cells_log2));
      if (!p) {
        problems.push_back("level " + std::to_string(l) + ": the parent of cell " + std::to_string(child.map.slots[c]) +
                           " is not in the map");
        continue;
      }
      const std::uint32_t parent_front = parent.data.front[*p];
      for (std::size_t side = 0; side < 2; ++side) {
        const std::uint32_t stands_for = side == 0 ? front : shared::NegatedFront(front);
        const std::size_t to = shared::FacesFront(stands_for, parent_front) ? 0 : 1;
        for (int ch = 0; ch < 3; ++ch) {
          sums[l][6 * *p + 3 * to + ch] += sums[l - 1][6 * c + 3 * side + ch];
        }
        counts[l][2 * *p + to] += counts[l - 1][2 * c + side];
      }
    }
  }
  for (std::size_t l = 0; l < cache.levels.size(); ++l) {
    CompareArray("fixed sum", 6, cache.levels[l], sums[l], cache.levels[l].data.fixed_sums, problems);
    CompareArray("count", 2, cache.levels[l], counts[l], cache.levels[l].data.counts, problems);
  }
  return problems;
}

}  // namespace hpsf
