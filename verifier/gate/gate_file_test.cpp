// The gate file's option words that CI matrices feed: --shard.
#include "verifier/gate/gate_file.h"

#include <utility>

#include <gtest/gtest.h>

#include "core/error.h"

namespace hpsf {
namespace {

// --shard I/N counts from 1: a CI matrix indexed from 0 must be refused (shard 0 would run no case and pass), as
// must I > N, N = 0 and anything that is not I/N.
TEST(ParseShard, AcceptsOneToNAndRefusesTheRest) {
  EXPECT_EQ(ParseShard("1/1"), std::make_pair(1u, 1u));
  EXPECT_EQ(ParseShard("2/4"), std::make_pair(2u, 4u));
  EXPECT_EQ(ParseShard("4/4"), std::make_pair(4u, 4u));
  for (const char* bad : {"0/4", "5/4", "1/0", "0/0", "1", "/4", "1/", "a/4", "1/4x", "-1/4", ""}) {
    EXPECT_THROW(ParseShard(bad), ConfigError) << bad;
  }
}

}  // namespace
}  // namespace hpsf
