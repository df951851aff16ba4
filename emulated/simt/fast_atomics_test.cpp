// Fast mode's atomics under the heaviest contention there is: worker threads applying read-modify-writes to one
// word through DeviceMemory::ApplyConcurrently in a tight loop, as fast mode does from all cores. The final words
// must be exact. Measured on a 2-core machine with each atomic replaced by its racy form: a load-then-store add
// (integer or float) failed 5 runs of 5, a load-compare-store CAS 8 of 8 (with 2 x 2^22 tries).
#include <algorithm>
#include <bit>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "emulated/simt/device_memory.h"

namespace hpsf::simt {
namespace {

constexpr std::uint32_t kWorkers = 2;
constexpr std::uint64_t kOpsPerWorker = std::uint64_t(1) << 20;
// A compare-and-swap split into a load and a store loses only when the other thread writes in between: more
// tries.
constexpr std::uint64_t kCasOpsPerWorker = std::uint64_t(1) << 22;

// Runs `op` from kWorkers threads at once, each kOpsPerWorker times.
template <typename Op>
void Hammer(DeviceMemory& memory, Op op) {
  std::vector<std::thread> workers;
  for (std::uint32_t w = 0; w < kWorkers; ++w) {
    workers.emplace_back([&] {
      for (std::uint64_t i = 0; i < kOpsPerWorker; ++i) {
        MemoryOp m = op();
        memory.ApplyConcurrently(m);
      }
    });
  }
  for (std::thread& t : workers) t.join();
}

TEST(FastModeAtomics, IntegerAddsOnOneWordLoseNothing) {
  DeviceMemory memory;
  const std::uint32_t wide = memory.Allocate64("wide", 1), narrow = memory.Allocate32("narrow", 1);
  Hammer(memory, [&] { return MemoryOp{OpKind::kAtomicAdd, {wide, 0}, 3}; });
  Hammer(memory, [&] { return MemoryOp{OpKind::kAtomicAdd, {narrow, 0}, 1}; });
  EXPECT_EQ(memory.Words64(wide)[0], 3 * kWorkers * kOpsPerWorker);
  EXPECT_EQ(memory.Words32(narrow)[0], kWorkers * kOpsPerWorker);
}

TEST(FastModeAtomics, FloatAddsOnOneWordLoseNothing) {
  DeviceMemory memory;
  const std::uint32_t sum = memory.Allocate32("sum", 1);
  // 1.0 added 2^21 times: every partial sum is an integer below 2^24, so each add is exact in any order.
  Hammer(memory, [&] { return MemoryOp{OpKind::kAtomicAddFloat, {sum, 0}, std::bit_cast<std::uint32_t>(1.0f)}; });
  EXPECT_EQ(std::bit_cast<float>(memory.Words32(sum)[0]), float(kWorkers * kOpsPerWorker));
}

// Each worker ors its own bits, one after another, into one word shared by all: every bit arrives.
TEST(FastModeAtomics, OrsOnOneWordLoseNoBit) {
  DeviceMemory memory;
  const std::uint32_t word = memory.Allocate32("word", 1);
  std::vector<std::thread> workers;
  for (std::uint32_t w = 0; w < kWorkers; ++w) {
    workers.emplace_back([&, w] {
      for (std::uint32_t bit = w; bit < 32; bit += kWorkers) {
        MemoryOp m{OpKind::kAtomicOr, {word, 0}, std::uint64_t(1) << bit};
        memory.ApplyConcurrently(m);
      }
    });
  }
  for (std::thread& t : workers) t.join();
  EXPECT_EQ(memory.Words32(word)[0], 0xFFFFFFFFu);
}

// Exchanges pass tokens through one word: every token put in comes out exactly once (or stays in the word).
TEST(FastModeAtomics, ExchangesLoseAndDuplicateNothing) {
  DeviceMemory memory;
  const std::uint32_t word = memory.Allocate64("word", 1);
  std::vector<std::vector<std::uint64_t>> out(kWorkers);
  std::vector<std::thread> workers;
  for (std::uint32_t w = 0; w < kWorkers; ++w) {
    workers.emplace_back([&, w] {
      for (std::uint64_t i = 0; i < kOpsPerWorker / 64; ++i) {
        MemoryOp m{OpKind::kAtomicExchange, {word, 0}, (std::uint64_t(w) << 32) | (i + 1)};
        memory.ApplyConcurrently(m);
        out[w].push_back(m.result);
      }
    });
  }
  for (std::thread& t : workers) t.join();
  std::vector<std::uint64_t> all = {memory.Words64(word)[0]};
  for (const auto& o : out) all.insert(all.end(), o.begin(), o.end());
  std::sort(all.begin(), all.end());
  EXPECT_EQ(all[0], 0u);  // the word's first value came out once
  EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end());
  EXPECT_EQ(all.size(), kWorkers * (kOpsPerWorker / 64) + 1);
}

TEST(FastModeAtomics, CompareAndSwapIncrementsLoseNothing) {
  DeviceMemory memory;
  const std::uint32_t counter = memory.Allocate64("counter", 1);
  std::vector<std::thread> workers;
  for (std::uint32_t w = 0; w < kWorkers; ++w) {
    workers.emplace_back([&] {
      for (std::uint64_t i = 0; i < kCasOpsPerWorker; ++i) {
        MemoryOp load{OpKind::kLoad, {counter, 0}};
        memory.ApplyConcurrently(load);
        for (std::uint64_t seen = load.result;;) {
          MemoryOp cas{OpKind::kAtomicCas, {counter, 0}, seen + 1, seen};
          memory.ApplyConcurrently(cas);
          if (cas.result == seen) break;
          seen = cas.result;
        }
      }
    });
  }
  for (std::thread& t : workers) t.join();
  EXPECT_EQ(memory.Words64(counter)[0], kWorkers * kCasOpsPerWorker);
}

}  // namespace
}  // namespace hpsf::simt
