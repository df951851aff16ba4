// The HashCache's occupancy (core/occupancy.h, core/shared/occupancy.h) against a brute-force oracle, label
// `hashcache`. The oracle is CGAL's exact predicates: for every cell of a level, whether the closed cell box meets the
// triangle whose vertices hpsf rounded (FixedVertex; the rounded vertices are exact in double), by
// CGAL::do_intersect of the triangle, or of the segment or point a degenerate one is, and the box. Independent of
// hpsf's separating-axis test, and exact, so the two must agree cell for cell: on random triangles, on triangles
// whose vertices lie on the lattice of cell corners and faces (where they graze cells), in a grid plane, degenerate
// and tiny ones; at every level of the octree, and coarsening a level equals voxelizing the next. The device's
// occupancy (occupancy.comp, the same core/shared/occupancy.h compiled as GLSL) and the emulator's under every
// schedule are the reference's, bit for bit; a mark that sets its bit by a load and a store is a race the schedules
// find.

#include "core/occupancy.h"

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/shared/rng.h"
#include "emulated/occupancy_kernels.h"
#include "property_tests/racing_schedules.h"
#include "property_tests/vulkan_test_devices.h"
#include "tracer/scene_file.h"
#include "vulkan/occupancy_pass.h"

namespace hpsf::testing {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// A uniform float in [0, 1) from the counter RNG: draw `d` of triangle `t`.
float Draw(std::uint32_t t, std::uint32_t d) {
  return shared::RandomFloatFromPrefix(shared::RngPrefix(shared::RngCounter{7u, 0u, t, 0u, 0u}), d);
}

// The grid of 8 unit cells per axis at the world's origin.
shared::OccupancyGrid UnitGrid() {
  shared::OccupancyGrid grid;
  grid.cell_exponent = 0;
  grid.origin_x = grid.origin_y = grid.origin_z = 0;
  grid.resolution_log2 = 3;
  return grid;
}

Kernel::Point_3 Rounded(const shared::OccupancyGrid& grid, const glm::vec3& v) {
  const shared::FixedPoint3 p = shared::FixedVertex(grid, v);
  const double unit = std::ldexp(1.0, -shared::kOccupancyFractionBits);  // in finest cells
  return {double(p.x) * unit, double(p.y) * unit, double(p.z) * unit};
}

// The oracle: whether the closed box of cell (x, y, z) of `level` meets the rounded triangle.
bool OracleMeets(const shared::OccupancyGrid& grid, const OccupancyTriangle& t, int x, int y, int z, int level) {
  const double side = std::ldexp(1.0, level);
  const Kernel::Iso_cuboid_3 box(x * side, y * side, z * side, (x + 1) * side, (y + 1) * side, (z + 1) * side);
  const Kernel::Point_3 p[3] = {Rounded(grid, t[0]), Rounded(grid, t[1]), Rounded(grid, t[2])};
  const Kernel::Triangle_3 triangle(p[0], p[1], p[2]);
  if (!triangle.is_degenerate()) return CGAL::do_intersect(triangle, box);
  // Collinear: the segment between the two points farthest apart, or one point.
  int a = 0, b = 1;
  for (const auto& [i, j] : {std::pair{0, 2}, std::pair{1, 2}}) {
    if (CGAL::compare_squared_distance(p[i], p[j], CGAL::squared_distance(p[a], p[b])) == CGAL::LARGER) {
      a = i;
      b = j;
    }
  }
  if (p[a] == p[b]) return !box.has_on_unbounded_side(p[a]);
  return CGAL::do_intersect(Kernel::Segment_3(p[a], p[b]), box);
}

// The triangles the tests voxelize, in the unit grid's world coordinates [0, 8].
std::vector<OccupancyTriangle> TestTriangles() {
  std::vector<OccupancyTriangle> triangles;
  std::uint32_t t = 0, d = 0;
  const auto vertex = [&](int kind) {
    const auto coordinate = [&](std::uint32_t d) {
      const float u = Draw(t, d);
      switch (kind) {
        case 0:  // anywhere
          return 8.0f * u;
        case 1:  // on a cell corner, edge or face: whole or half cells
          return 0.5f * float(int(17.0f * u));
        default:  // on the lattice of 2^-8 of a cell, where rounding leaves it
          return float(int(2048.0f * u)) / 256.0f;
      }
    };
    d += 3;  // each vertex of a triangle its own three draws
    return glm::vec3(coordinate(d), coordinate(d + 1), coordinate(d + 2));
  };
  for (; t < 600; ++t) {
    const int kind = int(t % 3);
    OccupancyTriangle tri = {vertex(kind), vertex(kind), vertex(kind)};
    switch (t % 10) {
      case 7:  // in a grid plane
        tri[1].z = tri[2].z = tri[0].z = float(int(tri[0].z));
        break;
      case 8:  // collinear, or a point
        tri[2] = tri[0] + (tri[1] - tri[0]) * (t % 20 == 8 ? 0.5f : 0.0f);
        if (t % 40 == 18) tri[1] = tri[0];
        break;
      case 9:  // tiny, inside a cell or across a corner
        tri[1] = tri[0] + glm::vec3(0.01f, 0.0f, 0.0f);
        tri[2] = tri[0] + glm::vec3(0.0f, 0.01f, 0.01f);
        break;
      default:
        break;
    }
    triangles.push_back(tri);
  }
  return triangles;
}

std::vector<OccupancyTriangle> CornellTriangles() {
  std::vector<OccupancyTriangle> triangles;
  for (const Triangle& t : LoadScene("cornell").triangles) triangles.push_back({t.p0, t.p1, t.p2});
  return triangles;
}

// Every test triangle alone, at every level, cell for cell against the oracle.
TEST(Occupancy, EachTriangleOccupiesExactlyTheCellsItsClosedBoxesMeet) {
  const shared::OccupancyGrid grid = UnitGrid();
  const std::vector<OccupancyTriangle> triangles = TestTriangles();
  std::uint64_t occupied = 0, checked = 0, grazed = 0;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const OccupancyTriangle& t = triangles[i];
    for (int level = 0; level <= grid.resolution_log2; ++level) {
      const OccupancyLevel field = VoxelizeTriangles(grid, {&t, 1}, level);
      const int n = field.cells_per_axis();
      for (int z = 0; z < n; ++z) {
        for (int y = 0; y < n; ++y) {
          for (int x = 0; x < n; ++x) {
            const bool want = OracleMeets(grid, t, x, y, z, level);
            ASSERT_EQ(field.Occupied(x, y, z), want)
                << "triangle " << i << " (" << t[0].x << " " << t[0].y << " " << t[0].z << " / " << t[1].x << " "
                << t[1].y << " " << t[1].z << " / " << t[2].x << " " << t[2].y << " " << t[2].z << "), level " << level
                << ", cell " << x << " " << y << " " << z;
            ++checked;
            occupied += want;
          }
        }
      }
      // Grazed: cells the triangle meets at their boundary only, which a slightly smaller box would miss.
      if (level == 0) {
        for (int z = 0; z < n; ++z) {
          for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) {
              if (!field.Occupied(x, y, z)) continue;
              const double e = 1.0 / 1024.0;
              const Kernel::Iso_cuboid_3 inner(x + e, y + e, z + e, x + 1 - e, y + 1 - e, z + 1 - e);
              const Kernel::Point_3 p[3] = {Rounded(grid, t[0]), Rounded(grid, t[1]), Rounded(grid, t[2])};
              const Kernel::Triangle_3 tri(p[0], p[1], p[2]);
              if (!tri.is_degenerate() && !CGAL::do_intersect(tri, inner)) ++grazed;
            }
          }
        }
      }
    }
  }
  std::printf("%zu triangles, %llu cells checked over 4 levels, %llu occupied, %llu of them only grazed\n",
              triangles.size(), (unsigned long long)checked, (unsigned long long)occupied, (unsigned long long)grazed);
  EXPECT_GT(grazed, 100u) << "the triangles do not exercise the boxes' boundaries";
}

// A level coarsened from the one below equals that level voxelized directly, and the pyramid's root is one cell.
TEST(Occupancy, CoarseningALevelEqualsVoxelizingTheNext) {
  const shared::OccupancyGrid grid = UnitGrid();
  const std::vector<OccupancyTriangle> all = TestTriangles();
  for (std::size_t first = 0; first < all.size(); first += 50) {
    const std::span<const OccupancyTriangle> some(all.data() + first, 5);
    const std::vector<OccupancyLevel> pyramid = OccupancyPyramid(grid, some);
    ASSERT_EQ(pyramid.size(), 4u);
    for (int level = 1; level <= grid.resolution_log2; ++level) {
      EXPECT_TRUE(pyramid[level] == VoxelizeTriangles(grid, some, level))
          << "triangles " << first << ", level " << level;
    }
    EXPECT_EQ(pyramid.back().Count(), 1u);
  }
}

// The grid over a built-in scene: every vertex inside it, the finest cell the least power of two that holds the
// scene; each level of the Cornell box at 2^7 cells per axis, coarsened, equals it voxelized directly, and the
// density halves roughly from level to level as Roth's Table 1 does (surfaces: a quarter of the cells, times 8).
TEST(Occupancy, TheCornellBoxsLevels) {
  const std::vector<OccupancyTriangle> triangles = CornellTriangles();
  const shared::OccupancyGrid grid = GridOver(triangles, 7, "cornell");
  for (const OccupancyTriangle& t : triangles) {
    for (const glm::vec3& v : t) {
      const shared::FixedPoint3 p = shared::FixedVertex(grid, v);
      for (const std::int64_t c : {p.x, p.y, p.z}) {
        EXPECT_GE(c, 0);
        EXPECT_LE(c, std::int64_t(128) << shared::kOccupancyFractionBits);
      }
    }
  }
  const std::vector<OccupancyLevel> pyramid = OccupancyPyramid(grid, triangles);
  std::printf("cornell, finest cell 2^%d:", grid.cell_exponent);
  for (const OccupancyLevel& level : pyramid) {
    const double cells = std::pow(double(level.cells_per_axis()), 3.0);
    std::printf(" %d^3 %.4f", level.cells_per_axis(), double(level.Count()) / cells);
    if (level.level() > 0 && level.level() < 4) {
      EXPECT_TRUE(level == VoxelizeTriangles(grid, triangles, level.level())) << "level " << level.level();
    }
  }
  std::printf("\n");
  // At least the five walls of the box, each some (extent / cell)^2 cells.
  float low = triangles[0][0].x, high = low;
  for (const OccupancyTriangle& t : triangles) {
    for (const glm::vec3& v : t) {
      low = std::min(low, v.x);
      high = std::max(high, v.x);
    }
  }
  const double across = std::floor((double(high) - low) / std::ldexp(1.0, grid.cell_exponent));
  EXPECT_GT(double(pyramid[0].Count()), 5.0 * across * across);
}

// The test triangles spread over a grid of 2^8 unit cells per axis, each in a region of its own 16 cells a side, so
// that a cell one triangle misses is not filled by another's.
std::vector<OccupancyTriangle> SpreadTestTriangles() {
  std::vector<OccupancyTriangle> spread = TestTriangles();
  for (std::size_t i = 0; i < spread.size(); ++i) {
    const glm::vec3 offset(16.0f * float(i % 16), 16.0f * float((i / 16) % 16), 16.0f * float(i / 256));
    for (glm::vec3& v : spread[i]) v += offset;
  }
  return spread;
}

// On Vulkan (mapped and staged): the test triangles spread over 2^8 cells per axis at levels 0 to 3, and the Cornell
// box at 2^7 cells per axis, each field the reference's bit for bit and its count by popcount and atomic add the
// field's.
TEST(Occupancy, TheDevicesFieldIsTheReferences) {
  const std::vector<OccupancyTriangle> test = SpreadTestTriangles();
  shared::OccupancyGrid test_grid = UnitGrid();
  test_grid.resolution_log2 = 8;
  const std::vector<OccupancyTriangle> cornell = CornellTriangles();
  const shared::OccupancyGrid cornell_grid = GridOver(cornell, 7, "cornell");
  for (const StagingPolicy staging : {StagingPolicy::kNever, StagingPolicy::kAlways}) {
    VulkanDevice& device = TestDevice(staging);
    for (int level = 0; level <= 3; ++level) {
      const DeviceOccupancy on_device = VoxelizeOnDevice(device, test_grid, test, level);
      const OccupancyLevel reference = VoxelizeTriangles(test_grid, test, level);
      EXPECT_TRUE(on_device.field == reference) << "test triangles, level " << level;
      EXPECT_EQ(on_device.counted, reference.Count()) << "test triangles, level " << level;
    }
    const DeviceOccupancy on_device = VoxelizeOnDevice(device, cornell_grid, cornell);
    const OccupancyLevel reference = VoxelizeTriangles(cornell_grid, cornell);
    EXPECT_TRUE(on_device.field == reference) << "cornell";
    EXPECT_EQ(on_device.counted, reference.Count()) << "cornell";
    std::printf("%s: cornell at 128^3, %llu cells occupied on the device and in the reference\n",
                staging == StagingPolicy::kNever ? "mapped" : "staged", (unsigned long long)on_device.counted);
  }
}

// The emulator's marks and count, in fast mode on one and two workers and under the 41 racing schedules (random and
// PCT with warps of 4, and the serial order), give the reference's field for the spread test triangles at levels 0
// and 2 and for the Cornell box; the dense test triangles (600 in 8^3 cells, most words set by many) likewise. The
// broken mark, a load and a store for its or, loses bits under some of the 40 faithful schedules.
TEST(Occupancy, TheEmulatorsFieldIsTheReferencesUnderEverySchedule) {
  const std::vector<OccupancyTriangle> spread = SpreadTestTriangles();
  shared::OccupancyGrid spread_grid = UnitGrid();
  spread_grid.resolution_log2 = 8;
  const std::vector<OccupancyTriangle> dense = TestTriangles();
  const std::vector<OccupancyTriangle> cornell = CornellTriangles();
  const shared::OccupancyGrid cornell_grid = GridOver(cornell, 6, "cornell");
  std::vector<EmulatorOptions> schedules = RacingSchedules();
  EmulatorOptions two;
  two.threads = 2;
  schedules.push_back(two);
  int lost = 0;
  for (const EmulatorOptions& options : schedules) {
    const std::string name =
        options.mode == simt::Mode::kFast ? "fast, " + std::to_string(options.threads) + " threads" : options.schedule;
    for (const int level : {0, 2}) {
      const EmulatedOccupancy run = VoxelizeEmulated(spread_grid, spread, level, options);
      EXPECT_TRUE(run.field == VoxelizeTriangles(spread_grid, spread, level)) << name << ", level " << level;
      EXPECT_EQ(run.counted, run.field.Count()) << name;
    }
    const OccupancyLevel dense_reference = VoxelizeTriangles(UnitGrid(), dense);
    EXPECT_TRUE(VoxelizeEmulated(UnitGrid(), dense, 0, options).field == dense_reference) << name;
    EXPECT_TRUE(VoxelizeEmulated(cornell_grid, cornell, 0, options).field == VoxelizeTriangles(cornell_grid, cornell))
        << name;
    if (options.mode == simt::Mode::kFast) continue;  // the broken mark on two workers is timing's, not a seed's
    const EmulatedOccupancy broken = VoxelizeEmulated(UnitGrid(), dense, 0, options, true);
    if (!(broken.field == dense_reference)) {
      if (lost++ == 0) {
        std::printf("%s: the load-and-store mark keeps %llu of the %llu occupied cells\n", name.c_str(),
                    (unsigned long long)broken.field.Count(), (unsigned long long)dense_reference.Count());
      }
    }
  }
  std::printf("the load-and-store mark lost bits under %d of the 40 faithful schedules\n", lost);
  EXPECT_GT(lost, 0);
}

// Every order of two triangles' marks, enumerated: each meets one cell of the same word. The atomic or gives the
// field of both under every order; the load-and-store mark loses one bit where both loads come before either store.
TEST(Occupancy, EveryOrderOfTwoMarksOfOneWordIsExplored) {
  const shared::OccupancyGrid grid = UnitGrid();
  // Tiny triangles inside cells (0, 0, 0) and (1, 0, 0): one word, two bits.
  const std::vector<OccupancyTriangle> two = {
      {glm::vec3(0.25f), glm::vec3(0.5f, 0.25f, 0.25f), glm::vec3(0.25f, 0.5f, 0.25f)},
      {glm::vec3(1.25f, 0.25f, 0.25f), glm::vec3(1.5f, 0.25f, 0.25f), glm::vec3(1.25f, 0.5f, 0.25f)}};
  const OccupancyLevel expected = VoxelizeTriangles(grid, two);
  ASSERT_EQ(expected.Count(), 2u);
  const auto explore = [&](bool broken) {
    return ExploreEveryOrder(EmulatorOptions{}, [&](const EmulatorOptions& each) {
      return !(VoxelizeEmulated(grid, two, 0, each, broken).field == expected);
    });
  };
  const Exploration correct = explore(false);
  const Exploration racing = explore(true);
  std::printf(
      "two marks of one word, exhaustive: atomic or %llu orders, all equal; load and store loses a bit in %llu "
      "of %llu\n",
      (unsigned long long)correct.schedules, (unsigned long long)racing.caught, (unsigned long long)racing.schedules);
  EXPECT_EQ(correct.caught, 0u);
  EXPECT_GT(racing.caught, 0u);
  EXPECT_LT(racing.caught, racing.schedules);
}

TEST(Occupancy, ABadGridIsAnInputErrorNamingItsSource) {
  const std::vector<OccupancyTriangle> one = {
      {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)}};
  const auto fails = [](std::span<const OccupancyTriangle> triangles, int resolution_log2, const std::string& what) {
    try {
      GridOver(triangles, resolution_log2, "scene.json");
      ADD_FAILURE() << what << ": no error";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("scene.json: ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fails({}, 4, "no triangle");
  fails(one, 1, "resolution");
  fails(one, 11, "resolution");
  std::vector<OccupancyTriangle> bad = one;
  bad[0][1].y = std::nanf("");
  fails(bad, 4, "not finite");
  std::vector<OccupancyTriangle> far = one;
  for (glm::vec3& v : far[0]) v = v * 1e-6f + glm::vec3(1e6f);
  fails(far, 10, "too far");
  // 16 cells of 2^-4 end at the unit triangle's far vertices, whose cell index (16) lies outside: 2^-3.
  EXPECT_EQ(GridOver(one, 4, "scene.json").cell_exponent, -3);
}

}  // namespace
}  // namespace hpsf::testing
