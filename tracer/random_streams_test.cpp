// The tracer's random streams: every (seed, frame) is a stream of its own. A tracer that folded the frame into the
// seed would make frame f of seed s repeat frame 0 of seed s + f, and every backend, sharing the records, would
// agree with it: only a statement about the streams themselves catches it.
#include <cstring>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/shared/rng.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

// The counter RNG: 16 seeds x 16 frames, the first 64 words of each (pixel, dimension) stream, pairwise distinct.
TEST(RandomStreams, EverySeedAndFrameIsAStreamOfItsOwn) {
  std::vector<std::vector<std::uint32_t>> streams;
  for (std::uint32_t seed = 0; seed < 16; ++seed) {
    for (std::uint32_t frame = 0; frame < 16; ++frame) {
      std::vector<std::uint32_t> words;
      for (std::uint32_t pixel = 0; pixel < 64; ++pixel)
        words.push_back(shared::RandomBits({seed, frame, pixel, 0u, 0u}, 0u));
      streams.push_back(std::move(words));
    }
  }
  for (std::size_t a = 0; a < streams.size(); ++a) {
    for (std::size_t b = a + 1; b < streams.size(); ++b) {
      EXPECT_NE(streams[a], streams[b]) << "streams " << a << " and " << b << " (seed * 16 + frame)";
    }
  }
}

// The tracer on a static scene (the frame changes nothing but the random numbers): seed s frame f never traces the
// records of another (seed, frame), in particular not those of seed s + f, frame 0.
TEST(RandomStreams, TheTracersSeedsAndFramesTraceDifferentPaths) {
  const Scene scene = LoadScene("cornell");
  std::vector<std::pair<std::pair<std::uint32_t, std::uint32_t>, RecordBatch>> traced;
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    for (std::uint32_t frame = 0; frame <= 2; ++frame) {
      TraceOptions options;
      options.width = options.height = 8;
      options.samples_per_pixel = 1;
      options.seed = seed;
      options.frame = frame;
      traced.push_back({{seed, frame}, TraceRecords(scene, options).batch});
    }
  }
  for (std::size_t a = 0; a < traced.size(); ++a) {
    for (std::size_t b = a + 1; b < traced.size(); ++b) {
      const RecordBatch &x = traced[a].second, &y = traced[b].second;
      ASSERT_EQ(x.records.size(), y.records.size());
      EXPECT_NE(std::memcmp(x.records.data(), y.records.data(), x.records.size() * sizeof(Record)), 0)
          << "seed " << traced[a].first.first << " frame " << traced[a].first.second << " traces the records of seed "
          << traced[b].first.first << " frame " << traced[b].first.second;
    }
  }
}

}  // namespace
}  // namespace hpsf
