// The sweep's grid (tools/hpsf/sweep_grid.h): every combination in order, the last axis fastest; what a method
// ignores merged into one configuration; bad grids refused naming --grid.
#include "tools/hpsf/sweep_grid.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace hpsf {
namespace {

std::vector<std::string> Ids(const std::string& grid) {
  std::vector<std::string> ids;
  for (const SweepConfig& c : ExpandGrid(ParseGrid(grid))) ids.push_back(c.id);
  return ids;
}

TEST(SweepGrid, EveryCombinationLastAxisFastest) {
  EXPECT_EQ(
      Ids("spp=1,4; filter-width=2,8"),
      (std::vector<std::string>{
          "method=hpsf backend=reference spp=1 filter-width=2", "method=hpsf backend=reference spp=1 filter-width=8",
          "method=hpsf backend=reference spp=4 filter-width=2", "method=hpsf backend=reference spp=4 filter-width=8"}));
}

TEST(SweepGrid, WhatAMethodIgnoresIsOneConfiguration) {
  // pt ignores the backend and the filter; radius the backend: 1 + 2 x 2 + 2 configurations, not 12.
  EXPECT_EQ(Ids("method=pt,hpsf,radius; backend=reference,emulated; jitter=0,1"),
            (std::vector<std::string>{
                "method=pt backend=- spp=4", "method=hpsf backend=reference spp=4 jitter=0",
                "method=hpsf backend=reference spp=4 jitter=1", "method=hpsf backend=emulated spp=4 jitter=0",
                "method=hpsf backend=emulated spp=4 jitter=1", "method=radius backend=- spp=4 jitter=0",
                "method=radius backend=- spp=4 jitter=1"}));
  const std::vector<SweepConfig> configs = ExpandGrid(ParseGrid("normal=none; accum=float32"));
  ASSERT_EQ(configs.size(), 1u);
  EXPECT_EQ(configs[0].FilterArguments(), (std::vector<std::string>{"--normal", "none", "--accum", "float32"}));
}

TEST(SweepGrid, FramesAndTraceAxesGoWhereTheMethodReadsThem) {
  // frames applies to every method; max-depth to the methods tracing whole paths; filtered-vertices to the two with
  // the transport; continuation-depth to anhpsf alone. What a method ignores merges: 2 x (2 + 2 + 2 + 2) = 16, not 32.
  const std::vector<SweepConfig> configs = ExpandGrid(ParseGrid(
      "frames=1,16; method=pt,hpsf,nhpsf,anhpsf; max-depth=2,8; filtered-vertices=1,2; continuation-depth=8"));
  std::vector<std::string> ids;
  for (const SweepConfig& c : configs) ids.push_back(c.id);
  EXPECT_EQ(ids,
            (std::vector<std::string>{
                "method=pt backend=- spp=4 max-depth=2", "method=pt backend=- spp=4 max-depth=8",
                "method=hpsf backend=reference spp=4 max-depth=2", "method=hpsf backend=reference spp=4 max-depth=8",
                "method=nhpsf backend=reference spp=4 filtered-vertices=1",
                "method=nhpsf backend=reference spp=4 filtered-vertices=2",
                "method=anhpsf backend=reference spp=4 filtered-vertices=1 continuation-depth=8",
                "method=anhpsf backend=reference spp=4 filtered-vertices=2 continuation-depth=8",
                "method=pt backend=- spp=4 frames=16 max-depth=2", "method=pt backend=- spp=4 frames=16 max-depth=8",
                "method=hpsf backend=reference spp=4 frames=16 max-depth=2",
                "method=hpsf backend=reference spp=4 frames=16 max-depth=8",
                "method=nhpsf backend=reference spp=4 frames=16 filtered-vertices=1",
                "method=nhpsf backend=reference spp=4 frames=16 filtered-vertices=2",
                "method=anhpsf backend=reference spp=4 frames=16 filtered-vertices=1 continuation-depth=8",
                "method=anhpsf backend=reference spp=4 frames=16 filtered-vertices=2 continuation-depth=8"}));
  EXPECT_EQ(configs[8].frames, 16u);
  EXPECT_EQ(configs[0].max_depth, 2);
  EXPECT_FALSE(configs[4].max_depth);
  EXPECT_EQ(configs[7].filtered_vertices, 2u);
  EXPECT_EQ(configs[7].continuation_depth, 8u);
  EXPECT_TRUE(configs[4].Hashed() && configs[4].Transports());
  EXPECT_TRUE(configs[2].Hashed() && !configs[2].Transports());
  EXPECT_FALSE(configs[0].Hashed());
  // No frames axis, or frames=1: the ids of before.
  EXPECT_EQ(Ids("frames=1; method=pt"), (std::vector<std::string>{"method=pt backend=- spp=4"}));
}

// The HashCache's axes belong to it alone: other methods merge over them, and it ignores max-depth (its paths have
// l_store + l_len vertices) but keeps its backend.
TEST(SweepGrid, TheHashCachesAxesAreItsOwn) {
  EXPECT_EQ(Ids("method=pt,hashcache; cache-resolution=5,6; backend=reference,vulkan; max-depth=3"),
            (std::vector<std::string>{"method=pt backend=- spp=4 max-depth=3",
                                      "method=hashcache backend=reference spp=4 cache-resolution=5",
                                      "method=hashcache backend=vulkan spp=4 cache-resolution=5",
                                      "method=hashcache backend=reference spp=4 cache-resolution=6",
                                      "method=hashcache backend=vulkan spp=4 cache-resolution=6"}));
}

TEST(SweepGrid, BadGridsNameTheGrid) {
  for (const char* grid : {"",
                           "spp",
                           "spp=0",
                           "spp=4,x",
                           "method=kd",
                           "backend=gpu",
                           "spp=1; spp=2",
                           "--jitter=1",
                           "jitter=1,,2",
                           "frames=0",
                           "frames=4097",
                           "frames=2x",
                           "max-depth=-2",
                           "max-depth=1025",
                           "filtered-vertices=0",
                           "filtered-vertices=9",
                           "continuation-depth=0",
                           "continuation-depth=1025",
                           "transport=on",
                           "cache-resolution=1",
                           "cache-resolution=11",
                           "cache-store=0",
                           "cache-store=9",
                           "cache-length=0",
                           "cache-length=x",
                           "cache-update=locks"}) {
    SCOPED_TRACE(grid);
    try {
      ParseGrid(grid);
      ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("--grid"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace hpsf
