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

TEST(SweepGrid, BadGridsNameTheGrid) {
  for (const char* grid :
       {"", "spp", "spp=0", "spp=4,x", "method=kd", "backend=gpu", "spp=1; spp=2", "--jitter=1", "jitter=1,,2"}) {
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
