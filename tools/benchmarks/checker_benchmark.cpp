// The table checker's cost per record under each probing scheme: the Cornell box at 1080p, 1 spp (2 million
// records) filtered by the emulator into 2^21 slots (roomy) and 2^18 slots (crowded: probe failures and long
// windows), then judged by CheckTable alone, one thread. Run:
//   build/default/bin/checker_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "emulated/emulated_filter.h"
#include "tools/benchmarks/cornell_frame.h"
#include "verifier/checker/table_checker.h"

namespace hpsf {
namespace {

void BM_CheckTable(benchmark::State& state) {
  FilterConfig config;
  config.probing = ProbeKind(state.range(0));
  config.capacity = std::uint32_t(state.range(1));
  config.probe_limit = 16;
  const RecordBatch& batch = CornellFrame();
  const EmulatedRun run = EmulatedFilter(batch, config, EmulatorOptions{});
  for (auto _ : state) {
    const std::vector<TableViolation> violations = CheckTable({run.table, batch.records, run.keys, run.placements});
    if (!violations.empty()) state.SkipWithError(violations.front().ToString().c_str());
  }
  state.SetLabel(ToString(config.probing) + ":16");
  state.counters["probe_failures"] = double(run.probe_failures);
  state.counters["ns_per_record"] = benchmark::Counter(
      double(kFrameRecords), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_CheckTable)
    ->ArgsProduct({{0, 1, 2}, {1 << 21, 1 << 18}})
    ->ArgNames({"scheme", "slots"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace hpsf

BENCHMARK_MAIN();
