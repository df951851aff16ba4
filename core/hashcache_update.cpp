#include "core/hashcache_update.h"

#include <algorithm>
#include <array>
#include <optional>

#include "core/format.h"
#include "core/shared/fixed_point.h"
#include "core/shared/hashcache_cell.h"

namespace hpsf {
namespace {

struct Element {
  std::uint32_t key = 0;     // the cell at the current level
  std::uint32_t side = 0;    // a front word: the sample's normal, or the finer cell's side
  std::uint32_t origin = 0;  // the sample's index, or the finer segment's word
  std::array<std::uint64_t, 3> fixed{};
  std::array<float, 3> light{};
  std::uint64_t count = 1;
  std::uint32_t slot = 0;   // located
  std::uint64_t order = 0;  // segment word << 32 | origin, once claimed
};

std::vector<Element> SampleElements(const HashCache& cache, std::span<const HashCacheSample> samples,
                                    HashCacheUpdateReport& report) {
  const float scale = SumScale(cache.accumulation, cache.fixed_point_bits);
  const int cells_log2 = cache.grid.resolution_log2;
  std::vector<Element> elements;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const HashCacheSample& s = samples[i];
    const glm::ivec3 cell = shared::PointCell(cache.grid, s.position);
    if (cell.x < 0) {
      ++report.missed;
      continue;
    }
    Element e;
    e.key = shared::CuckooKey(cell.x, cell.y, cell.z, cells_log2);
    e.side = shared::FrontWord(s.normal);
    e.origin = std::uint32_t(i);
    for (int c = 0; c < 3; ++c) {
      e.light[c] = shared::Flush(s.light[c]);  // as a device without denormals would read it
      if (cache.accumulation == Accumulation::kFixed64) e.fixed[c] = shared::ToFixedPoint(e.light[c], scale);
    }
    elements.push_back(e);
  }
  return elements;
}

std::string Where(const HashCacheLevel& level, std::uint32_t slot, std::uint32_t key) {
  return "level " + std::to_string(level.level) + ", slot " + std::to_string(slot) + " (cell " + std::to_string(key) +
         ")";
}

// One level's claims in a frame: each unclaimed cell an element reaches is claimed with the element's side, or with
// the claim given (a backend's), which must then be the side of some element that reached it.
class LevelClaims {
 public:
  LevelClaims(HashCacheLevel& level, const std::vector<std::vector<std::uint32_t>>* claims)
      : level_(level),
        given_(claims ? &(*claims)[std::size_t(level.level)] : nullptr),
        claimed_now_(level.data.front.size(), 0),
        seen_(level.data.front.size(), 0) {}

  // The cell's front once `side` reached its slot.
  std::uint32_t Reach(std::uint32_t slot, std::uint32_t key, std::uint32_t side, HashCacheUpdateReport& report) {
    std::uint32_t& front = level_.data.front[slot];
    if (front == shared::kFrontUnclaimed) {
      front = given_ ? (*given_)[slot] : side;
      claimed_now_[slot] = 1;
      if (front == shared::kFrontUnclaimed) {
        report.problems.push_back(Where(level_, slot, key) + ": reached but left unclaimed");
        front = side;  // judge the rest of the frame as if it had claimed
      }
    }
    if (claimed_now_[slot] && side == front) seen_[slot] = 1;
    return front;
  }

  // Each claim given that no element's side made.
  void Report(HashCacheUpdateReport& report) const {
    if (!given_) return;
    for (std::size_t slot = 0; slot < claimed_now_.size(); ++slot) {
      if (claimed_now_[slot] && !seen_[slot]) {
        report.problems.push_back(Where(level_, std::uint32_t(slot), level_.map.slots[slot]) + ": front " +
                                  FormatHex(level_.data.front[slot]) +
                                  " is the side of no element that reached the cell");
      }
    }
  }

 private:
  HashCacheLevel& level_;
  const std::vector<std::uint32_t>* given_;
  std::vector<std::uint8_t> claimed_now_, seen_;
};

// The atomics rule: every sample at every level, on its own normal's side. Claims as UpdateHashCache's.
HashCacheUpdateReport UpdateByAtomics(HashCache& cache, std::span<const HashCacheSample> samples,
                                      const std::vector<std::vector<std::uint32_t>>* claims) {
  HashCacheUpdateReport report;
  const float scale = SumScale(cache.accumulation, cache.fixed_point_bits);
  std::vector<glm::ivec3> cells;
  for (const HashCacheSample& s : samples) cells.push_back(shared::PointCell(cache.grid, s.position));
  for (HashCacheLevel& level : cache.levels) {
    HashCacheData& data = level.data;
    LevelClaims level_claims(level, claims);
    std::uint64_t updated = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (cells[i].x < 0) {
        report.missed += level.level == 0;
        continue;
      }
      const glm::ivec3 cell = cells[i] >> level.level;
      const std::uint32_t key = shared::CuckooKey(cell.x, cell.y, cell.z, level.cells_log2);
      const std::optional<std::uint32_t> slot = level.map.Find(key);
      if (!slot) {
        report.missed += level.level == 0;
        continue;
      }
      const std::uint32_t side = shared::FrontWord(samples[i].normal);
      const std::uint32_t front = level_claims.Reach(*slot, key, side, report);
      const std::size_t back = shared::FacesFront(side, front) ? 0 : 1;
      for (int c = 0; c < 3; ++c) {
        data.fixed_sums[6 * *slot + 3 * back + c] += shared::ToFixedPoint(shared::Flush(samples[i].light[c]), scale);
      }
      data.counts[2 * *slot + back] += 1;
      ++updated;
    }
    report.segments.push_back(updated);
    level_claims.Report(report);
  }
  return report;
}

}  // namespace

HashCacheUpdateReport UpdateHashCache(HashCache& cache, std::span<const HashCacheSample> samples,
                                      const std::vector<std::vector<std::uint32_t>>* claims) {
  if (cache.update == HashCacheUpdateRule::kAtomics) return UpdateByAtomics(cache, samples, claims);
  HashCacheUpdateReport report;
  std::vector<Element> elements = SampleElements(cache, samples, report);
  for (HashCacheLevel& level : cache.levels) {
    HashCacheData& data = level.data;
    // 1. Locate and claim. A claim given is legitimate where some element reaching the cell has it as its side.
    std::vector<Element> located;
    LevelClaims level_claims(level, claims);
    for (Element& e : elements) {
      const std::optional<std::uint32_t> slot = level.map.Find(e.key);
      if (!slot) {
        if (level.level == 0) {
          ++report.missed;
        } else {
          report.problems.push_back("level " + std::to_string(level.level) + ": cell " + std::to_string(e.key) +
                                    " (the parent of a cell updated) is not in the map");
        }
        continue;
      }
      e.slot = *slot;
      const std::uint32_t front = level_claims.Reach(e.slot, e.key, e.side, report);
      const bool back = !shared::FacesFront(e.side, front);
      e.order = (std::uint64_t(shared::SegmentWord(e.key, back)) << 32) | e.origin;
      located.push_back(e);
    }
    level_claims.Report(report);
    // 2. Sort: the order words are distinct, so any sort gives this order.
    std::sort(located.begin(), located.end(), [](const Element& a, const Element& b) { return a.order < b.order; });
    // 3 and 4. Reduce each segment in order, update its cell's side once, and pass it up as an element.
    std::vector<Element> parents;
    std::uint64_t segments = 0;
    for (std::size_t head = 0; head < located.size();) {
      const std::uint32_t word = std::uint32_t(located[head].order >> 32);
      Element sum = located[head];
      std::size_t end = head + 1;
      for (; end < located.size() && std::uint32_t(located[end].order >> 32) == word; ++end) {
        for (int c = 0; c < 3; ++c) {
          sum.fixed[c] += located[end].fixed[c];
          sum.light[c] += located[end].light[c];
        }
        sum.count += located[end].count;
      }
      const bool back = shared::SegmentBack(word);
      const std::size_t side = back ? 1 : 0;
      for (int c = 0; c < 3; ++c) {
        if (cache.accumulation == Accumulation::kFixed64) {
          data.fixed_sums[6 * sum.slot + 3 * side + c] += sum.fixed[c];
        } else {
          data.float_sums[6 * sum.slot + 3 * side + c] += sum.light[c];
        }
      }
      data.counts[2 * sum.slot + side] += sum.count;
      ++segments;
      if (level.cells_log2 > 0) {
        Element up = sum;
        up.key = shared::ParentKey(sum.key, level.cells_log2);
        const std::uint32_t front = data.front[sum.slot];
        up.side = back ? shared::NegatedFront(front) : front;
        up.origin = word;
        parents.push_back(up);
      }
      head = end;
    }
    report.segments.push_back(segments);
    elements = std::move(parents);
  }
  return report;
}

}  // namespace hpsf
