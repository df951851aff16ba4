// The emulator's throughput on a 2-million-record batch (the Cornell box at 1080p, 1 spp) into a 2^21-slot table:
// fast mode beside the machine's own limit, a raw loop of four random 64-bit atomic adds per record over a
// table of the same size on all cores; fast mode as the backend runs frames (arrays kept) and in fresh memory; and
// faithful mode on a smaller batch for its slowdown; and the Vulkan host's read-back check over the same run. Run:
//   build/default/bin/emulator_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <atomic>
#include <vector>

#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>

#include "core/huge_pages.h"
#include "core/read_back_check.h"
#include "core/shared/hash.h"
#include "emulated/emulated_backend.h"
#include "emulated/emulated_filter.h"
#include "tools/benchmarks/cornell_frame.h"

namespace hpsf {
namespace {

constexpr std::uint32_t kSlots = 1u << 21;

FilterConfig TableConfig() {
  FilterConfig config;
  config.capacity = kSlots;
  config.probe_limit = 16;
  return config;
}

void BM_RawRandomAtomicAdds(benchmark::State& state) {
  // On huge pages, as the emulator's own table: the limit is the machine's best case.
  std::vector<std::uint64_t> table;
  ResizeOnHugePages(table, std::size_t(kSlots) * 4);
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, kFrameRecords, 4096), [&](const auto& range) {
      for (std::uint32_t i = range.begin(); i < range.end(); ++i) {
        const std::uint32_t slot = shared::Pcg(i) & (kSlots - 1);
        for (int c = 0; c < 4; ++c)
          std::atomic_ref<std::uint64_t>(table[std::size_t(c) * kSlots + slot]).fetch_add(1, std::memory_order_relaxed);
      }
    });
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_RawRandomAtomicAdds)->Unit(benchmark::kMillisecond)->UseRealTime();

void ReportRun(benchmark::State& state, const EmulatedRun& run) {
  state.counters["probe_failures"] = double(run.probe_failures);
  const EmulatedTimings& t = run.timings;
  for (const auto& [name, ms] : {std::pair{"keys_ms", t.keys_ms},
                                 {"F_ms", t.fixed_point_ms},
                                 {"clear_ms", t.clear_ms},
                                 {"accumulate_ms", t.accumulate_ms},
                                 {"read_back_ms", t.read_back_ms},
                                 {"resolve_ms", t.resolve_ms}}) {
    state.counters[name] = ms;
  }
}

// The backend as a renderer runs it, frame after frame (each a first frame here, after Reset): its arrays are
// kept from frame to frame, as a GPU backend keeps its buffers (emulated/emulator_workspace.h).
void BM_EmulatedFast(benchmark::State& state) {
  const RecordBatch& batch = CornellFrame();
  EmulatedBackend backend{EmulatorOptions{}};
  backend.FilterFrame(batch, TableConfig());  // the first frame touches its arrays' pages
  for (auto _ : state) {
    backend.Reset();
    benchmark::DoNotOptimize(backend.FilterFrame(batch, TableConfig()).pixels.data());
    ReportRun(state, backend.run());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_EmulatedFast)->Unit(benchmark::kMillisecond)->UseRealTime();

// Frames of the Cornell batch through one backend under `config`, its phases reported, labelled `label`.
void FilterFrames(benchmark::State& state, const FilterConfig& config, const std::string& label) {
  const RecordBatch& batch = CornellFrame();
  EmulatedBackend backend{EmulatorOptions{}};
  backend.FilterFrame(batch, config);  // the first frame touches its arrays' pages
  for (auto _ : state) {
    backend.Reset();
    benchmark::DoNotOptimize(backend.FilterFrame(batch, config).pixels.data());
    ReportRun(state, backend.run());
  }
  state.SetLabel(label);
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}

// The same with each key identity (0 fingerprints, 32-bit tags; 1 full keys, 64-bit tags, core/key_identity.h), so
// that their costs are read side by side in one run.
void BM_EmulatedKeyIdentity(benchmark::State& state) {
  FilterConfig config = TableConfig();
  config.key_identity = state.range(0) == 0 ? KeyIdentity::kFingerprint : KeyIdentity::kFull;
  FilterFrames(state, config, ToString(config.key_identity));
}
BENCHMARK(BM_EmulatedKeyIdentity)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// Voxels with few vertices, side by side in one run: multi-level accumulation (--levels 1, 2, 3, core/shared/levels.h)
// and the neighbourhood search (second argument 1: --neighbour-search, core/shared/neighbour_search.h), with
// --min-count 4 wherever either is on: what each coarser level adds to the accumulate, the threshold and the search
// to the resolve.
void BM_EmulatedLevels(benchmark::State& state) {
  FilterConfig config = TableConfig();
  config.levels = std::uint32_t(state.range(0));
  config.neighbour_search = state.range(1) != 0;
  config.min_count = config.levels > 1 || config.neighbour_search ? 4 : 1;
  FilterFrames(state, config, "levels " + std::to_string(config.levels) + (config.neighbour_search ? ", search" : ""));
}
BENCHMARK(BM_EmulatedLevels)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({3, 0})
    ->Args({1, 1})
    ->Args({3, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// What the Vulkan host adds to every frame: the read-back check of core/read_back_check.h (and the probe statistics
// it hands on to) over the 2M-record frame's run, one thread, beside the whole backend above.
void BM_ReadBackCheck(benchmark::State& state) {
  EmulatedBackend backend{EmulatorOptions{}};
  backend.FilterFrame(CornellFrame(), TableConfig());
  HashedRun run = backend.run();
  for (auto _ : state) {
    FinishReadBack(run, 0, "the benchmark's run");
    benchmark::DoNotOptimize(run.probe_lengths.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_ReadBackCheck)->Unit(benchmark::kMillisecond)->UseRealTime();

// A run in fresh memory, as the first frame of a process: each array's pages faulted in and zeroed by the kernel.
void BM_EmulatedFastFreshMemory(benchmark::State& state) {
  const RecordBatch& batch = CornellFrame();
  for (auto _ : state) {
    EmulatedRun run = EmulatedFilter(batch, TableConfig(), EmulatorOptions{});
    benchmark::DoNotOptimize(run.image.pixels.data());
    ReportRun(state, run);
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_EmulatedFastFreshMemory)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EmulatedFaithful(benchmark::State& state) {
  // The first rows of the same frame.
  static const RecordBatch batch = [&] {
    RecordBatch b = CornellFrame();
    b.height = std::uint32_t(state.range(0)) / b.width;
    b.records.resize(std::size_t(b.width) * b.height);
    return b;
  }();
  EmulatorOptions options;
  options.mode = simt::Mode::kFaithful;
  options.warp_size = 32;
  options.schedule = "random:1";
  FilterConfig config = TableConfig();
  for (auto _ : state) {
    EmulatedRun run = EmulatedFilter(batch, config, options);
    benchmark::DoNotOptimize(run.image.pixels.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * state.range(0));
}
BENCHMARK(BM_EmulatedFaithful)->Arg(1920 * 64)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace hpsf

BENCHMARK_MAIN();
