// Level seeding (core/level_seed.h) against hand-computed cells, not against another backend: every backend and the
// checker call SeedOf, so agreement between them cannot show that it seeds what Binder et al. §3.4.2 describe.
// A lookup over a map stands for the table before the frame; each case states the cell's neighbours and the seed
// worked out by hand.
#include <map>
#include <tuple>

#include <gtest/gtest.h>

#include "core/level_seed.h"
#include "core/shared/level_seed.h"

namespace hpsf {
namespace {

using Words = shared::KeyWords;

std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t> Key(const Words& w) {
  return {w.cell_x, w.cell_y, w.cell_z, w.level, w.normal};
}

Words Cell(int x, int y, int z, int level) {
  return Words{std::uint32_t(x), std::uint32_t(y), std::uint32_t(z), std::uint32_t(level + 128), 3u, 0u};
}

struct Table {
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>, CellState> cells;
  void Put(const Words& w, const CellState& state) { cells[Key(w)] = state; }
  CellLookup Lookup() const {
    return [this](const Words& w) -> std::optional<CellState> {
      const auto found = cells.find(Key(w));
      if (found == cells.end()) return std::nullopt;
      return found->second;
    };
  }
};

CellState Fixed(std::uint64_t count, std::uint64_t r, std::uint64_t g, std::uint64_t b) {
  CellState s;
  s.count = count;
  s.fixed_sum = {r, g, b};
  return s;
}

CellState Float(std::uint64_t count, float r, float g, float b) {
  CellState s;
  s.count = count;
  s.float_sum = {r, g, b};
  return s;
}

const Words kCell = Cell(-3, 5, 0, 2);

// The parent of (-3, 5, 0) at level 2 is (-2, 2, 0) at level 3 (floor(-3 / 2) = -2), and the cell is its child 3
// (x: -3 = 2 * -2 + 1, y: 5 = 2 * 2 + 1, z: 0). The children of the cell are (-6 or -5, 10 or 11, 0 or 1) at 1.
TEST(LevelSeedByHand, NeighboursAreTheCellsOfTheNextLevels) {
  const Words parent = shared::ParentKeyWords(kCell);
  EXPECT_EQ(Key(parent), Key(Cell(-2, 2, 0, 3)));
  EXPECT_EQ(Key(shared::ChildKeyWords(parent, 3)), Key(kCell));
  EXPECT_EQ(Key(shared::ChildKeyWords(kCell, 0)), Key(Cell(-6, 10, 0, 1)));
  EXPECT_EQ(Key(shared::ChildKeyWords(kCell, 7)), Key(Cell(-5, 11, 1, 1)));
  EXPECT_EQ(shared::ChildKeyWords(kCell, 5).normal, 3u);  // the normal bucket is kept
}

// Children and parent both hold samples: the children's sums and counts, added; the parent is not used (the
// resolution decreased: "simply add up").
TEST(LevelSeedByHand, ChildrenComeBeforeTheParent) {
  Table table;
  table.Put(shared::ChildKeyWords(kCell, 1), Fixed(3, 30, 300, 3000));
  table.Put(shared::ChildKeyWords(kCell, 6), Fixed(5, 7, 8, 9));
  table.Put(shared::ParentKeyWords(kCell), Fixed(800, 8000, 8000, 8000));
  const CellState s = SeedOf(kCell, {true, 0}, true, table.Lookup());
  EXPECT_EQ(s.count, 8u);
  EXPECT_EQ(s.fixed_sum, (std::array<std::uint64_t, 3>{37, 308, 3009}));
}

// Only the parent: an eighth of its count and sums, times 2^-S. Count 800, sums 8000, 1600, 805: at S = 0 100 and
// 1000, 200, 100 (805 >> 3 = 100, the shift rounds down); at S = 2, 25 and 250, 50, 25 (805 >> 5 = 25).
TEST(LevelSeedByHand, OnlyTheParentGivesItsShareShiftedByThreePlusS) {
  Table table;
  table.Put(shared::ParentKeyWords(kCell), Fixed(800, 8000, 1600, 805));
  const CellState s0 = SeedOf(kCell, {true, 0}, true, table.Lookup());
  EXPECT_EQ(s0.count, 100u);
  EXPECT_EQ(s0.fixed_sum, (std::array<std::uint64_t, 3>{1000, 200, 100}));
  const CellState s2 = SeedOf(kCell, {true, 2}, true, table.Lookup());
  EXPECT_EQ(s2.count, 25u);
  EXPECT_EQ(s2.fixed_sum, (std::array<std::uint64_t, 3>{250, 50, 25}));
  // float32: 64, 8 and 0.75 times 2^-3 and 2^-5.
  Table floats;
  floats.Put(shared::ParentKeyWords(kCell), Float(800, 64.0f, 8.0f, 0.75f));
  const CellState f0 = SeedOf(kCell, {true, 0}, false, floats.Lookup());
  EXPECT_EQ(f0.count, 100u);
  EXPECT_EQ(f0.float_sum, (std::array<float, 3>{8.0f, 1.0f, 0.09375f}));
  const CellState f2 = SeedOf(kCell, {true, 2}, false, floats.Lookup());
  EXPECT_EQ(f2.count, 25u);
  EXPECT_EQ(f2.float_sum, (std::array<float, 3>{2.0f, 0.25f, 0.0234375f}));
  EXPECT_EQ(f2.fixed_sum, (std::array<std::uint64_t, 3>{0, 0, 0}));
}

// A parent whose share of the count is 0 (fewer than 8 * 2^S samples) seeds nothing; neither does a cell with no
// neighbour, nor seeding turned off, whatever the neighbours hold.
TEST(LevelSeedByHand, TooSmallAParentNoNeighbourOrNoSeedingGiveNothing) {
  Table table;
  table.Put(shared::ParentKeyWords(kCell), Fixed(31, 3100, 3100, 3100));
  EXPECT_EQ(SeedOf(kCell, {true, 0}, true, table.Lookup()).count, 3u);
  const CellState none = SeedOf(kCell, {true, 2}, true, table.Lookup());  // 31 >> 5 = 0
  EXPECT_EQ(none.count, 0u);
  EXPECT_EQ(none.fixed_sum, (std::array<std::uint64_t, 3>{0, 0, 0}));
  EXPECT_EQ(SeedOf(kCell, {true, 0}, true, Table().Lookup()).count, 0u);
  EXPECT_EQ(SeedOf(kCell, {false, 0}, true, table.Lookup()).count, 0u);
}

// float32 children are added as floats in child order: 1e8 + 3 rounds to 1e8 (floats there are 8 apart), and
// - 1e8 leaves 0; the order 0, 2, 1 would leave 3.
TEST(LevelSeedByHand, Float32ChildrenAddInChildOrder) {
  Table table;
  table.Put(shared::ChildKeyWords(kCell, 0), Float(1, 1e8f, 1.0f, 1.0f));
  table.Put(shared::ChildKeyWords(kCell, 1), Float(1, 3.0f, 1.0f, 1.0f));
  table.Put(shared::ChildKeyWords(kCell, 2), Float(1, -1e8f, 1.0f, 1.0f));
  const CellState s = SeedOf(kCell, {true, 4}, false, table.Lookup());
  EXPECT_EQ(s.count, 3u);
  EXPECT_EQ(s.float_sum, (std::array<float, 3>{0.0f, 3.0f, 3.0f}));
}

}  // namespace
}  // namespace hpsf
