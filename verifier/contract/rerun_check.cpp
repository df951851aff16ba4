#include "verifier/contract/rerun_check.h"

#include <array>
#include <cstring>
#include <vector>

namespace hpsf {
namespace {

constexpr std::size_t kDifferencesShown = 20;

// Float sums bitwise, as core/image.h compares images; no memcmp on an empty vector's null data.
template <typename Floats>
bool SameBits(const std::vector<Floats>& a, const std::vector<Floats>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

// Touch t: record t mod n at t / n levels above its own cell (core/shared/levels.h).
std::uint32_t TouchSlot(const HashedRun& run, std::size_t touch) {
  const std::size_t n = run.placements.size();
  return LevelPlacement(run, touch % n, std::uint32_t(touch / n));
}
bool Placed(const HashedRun& run, std::size_t touch) { return TouchSlot(run, touch) < run.table.capacity; }

// Per record: placed in both runs or in neither, and its slot's count (and in fixed64 its sums) the same in both.
void CompareSlotsOfEachRecord(const HashedRun& first, const HashedRun& second, bool sums,
                              std::vector<std::string>& out) {
  const bool fixed = IntegerSums(first.table.accumulation);
  const std::size_t n = first.placements.size();
  for (std::size_t i = 0; i < n * first.table.levels && out.size() < kDifferencesShown; ++i) {
    const std::string record = "record " + std::to_string(i % n) +
                               (i >= n ? " (" + std::to_string(i / n) + " levels up)" : std::string()) + ": ";
    if (Placed(first, i) != Placed(second, i)) {
      out.push_back(record + "placed in one run and not in the other");
      continue;
    }
    if (!Placed(first, i)) continue;
    const std::uint32_t a = TouchSlot(first, i), b = TouchSlot(second, i);
    if (first.table.counts[a] != second.table.counts[b]) {
      out.push_back(record + "its slot's count is " + std::to_string(first.table.counts[a]) + " in one run (slot " +
                    std::to_string(a) + ") and " + std::to_string(second.table.counts[b]) + " in the other (slot " +
                    std::to_string(b) + ")");
    } else if (sums && fixed && first.table.fixed_sums[a] != second.table.fixed_sums[b]) {
      out.push_back(record + "its slot's fixed-point sums differ between the runs (slots " + std::to_string(a) +
                    " and " + std::to_string(b) + ")");
    } else if (sums && fixed && first.table.second_moments &&
               first.table.fixed_squares[a] != second.table.fixed_squares[b]) {
      out.push_back(record + "its slot's square sums differ between the runs (slots " + std::to_string(a) + " and " +
                    std::to_string(b) + ")");
    }
  }
}

void CompareWholeTables(const HashedRun& first, const HashedRun& second, std::vector<std::string>& out) {
  if (first.placements != second.placements || first.coarser_placements != second.coarser_placements)
    out.push_back("the placements differ");
  if (first.table.tags != second.table.tags) out.push_back("the tags differ");
  if (first.table.counts != second.table.counts) out.push_back("the counts differ");
  if (first.table.fixed_sums != second.table.fixed_sums) out.push_back("the fixed-point sums differ");
  if (!SameBits(first.table.float_sums, second.table.float_sums)) out.push_back("the float sums differ");
  if (first.table.fixed_squares != second.table.fixed_squares) out.push_back("the fixed-point square sums differ");
  if (!SameBits(first.table.float_squares, second.table.float_squares)) out.push_back("the float square sums differ");
}

}  // namespace

const char* ToString(RerunPromise promise) {
  switch (promise) {
    case RerunPromise::kEverything:
      return "ordered run: table, placements and image bit for bit";
    case RerunPromise::kCountsSumsAndImage:
      return "integer sums, nothing failed or aliased: each record's count and sums, and the image";
    case RerunPromise::kCountsAndSums:
      return "integer sums, nothing failed or aliased but a search's lookup: each record's count and sums (which "
             "cells a lookup finds follows the order of claims)";
    case RerunPromise::kCounts:
      return "float32, nothing failed or aliased: each record's count (sums follow the order of adds)";
    case RerunPromise::kNothing:
      return "probe failures or aliases: which records they hit follows the order of atomics";
  }
  return "?";
}

RerunPromise RerunPromiseFor(bool ordered, Accumulation accumulation, bool failed_or_aliased, bool lookup_aliased) {
  if (ordered) return RerunPromise::kEverything;
  if (failed_or_aliased) return RerunPromise::kNothing;
  if (!IntegerSums(accumulation)) return RerunPromise::kCounts;
  return lookup_aliased ? RerunPromise::kCountsAndSums : RerunPromise::kCountsSumsAndImage;
}

std::vector<std::string> CompareReruns(const HashedRun& first, const HashedRun& second, RerunPromise promise) {
  std::vector<std::string> out;
  if (promise == RerunPromise::kNothing) return out;
  if (first.placements.size() != second.placements.size()) return {"the runs placed different numbers of records"};
  switch (promise) {
    case RerunPromise::kEverything:
      CompareWholeTables(first, second, out);
      break;
    case RerunPromise::kCountsSumsAndImage:
    case RerunPromise::kCountsAndSums:
      CompareSlotsOfEachRecord(first, second, true, out);
      break;
    case RerunPromise::kCounts:
      CompareSlotsOfEachRecord(first, second, false, out);
      break;
    case RerunPromise::kNothing:
      break;
  }
  const bool image = promise == RerunPromise::kEverything || promise == RerunPromise::kCountsSumsAndImage;
  if (image && !SameBits(first.image, second.image)) out.push_back("the image changed");
  return out;
}

}  // namespace hpsf
