#include "tools/hpsf/stats_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "core/capture_file.h"
#include "core/error.h"
#include "core/footprint.h"
#include "core/key_batch.h"
#include "reference/reference_filter.h"
#include "tools/hpsf/batch_input.h"
#include "tools/hpsf/filter_options.h"
#include "tracer/path_tracer.h"
#include "verifier/contract/capture_judgement.h"
#include "verifier/gate/table_declaration.h"
#include "verifier/metrics/cell_variance.h"
#include "verifier/theory/table_statistics.h"

namespace hpsf {
namespace {

struct StatsOptions {
  std::string input;
  std::vector<std::string> given;  // the options given besides the input and --json: a capture takes none
  std::string size = "256x256";
  TraceOptions trace;
  FilterOptions filter;
  bool json = false;
};

void PrintRate(std::uint32_t value, const RateFigure& f) {
  char theory[32] = "-";
  if (f.judged) std::snprintf(theory, sizeof theory, "%.4g", f.theory);
  std::printf("  %-9u %12.4g %12s   [%.3g, %.3g]%s\n", value, f.Rate(), theory, f.low, f.high,
              f.ExceedsTheory() ? "   EXCEEDS THEORY" : "");
}

void PrintText(const TableStatistics& s, const std::string& input) {
  std::printf("%s: %llu records, %llu keyed, %llu distinct keys; capacity %u: load %.4f\n", input.c_str(),
              (unsigned long long)s.records, (unsigned long long)s.keyed_records, (unsigned long long)s.distinct_keys,
              s.capacity, s.load);
  if (!s.probe_histogram.empty()) {
    std::printf("probes of a successful search (linear probing, no limit): mean %.4f, theory %.4f\n", s.mean_probes,
                s.mean_probes_theory);
    for (std::size_t k = 0; k < s.probe_histogram.size(); ++k) {
      if (s.probe_histogram[k] == 0.0 && s.probe_histogram_theory[k] < 1e-6) continue;
      std::printf("  %s%-3zu %10.6f %10.6f\n", k + 1 == s.probe_histogram.size() ? ">=" : "  ", k + 1,
                  s.probe_histogram[k], s.probe_histogram_theory[k]);
    }
  }
  std::printf(
      "probe failures per probe limit under %s probing (keys in the batch's order; the bound counts failed keys as "
      "inserted%s):\n  %-9s %12s %12s   %s\n",
      ToString(s.probing).c_str(), s.probing == ProbeKind::kBucketWindow ? "; bucket-window has none, not judged" : "",
      "limit", "rate", "bound", "interval");
  for (const ProbeLimitFigure& f : s.probe_limits) PrintRate(f.probe_limit, f.failures);
  std::printf(
      "fingerprint aliases per width (probe limit %u%s):\n  %-9s %12s %12s   %s\n", s.probe_limit,
      s.key_identity == KeyIdentity::kFull ? "; what fingerprints would alias: this table stores full keys" : "",
      "bits", "rate", "predicted", "interval");
  for (const AliasFigure& f : s.fingerprints) PrintRate(f.fingerprint_bits, f.aliases);
  std::printf("  32 bits extrapolated: %.3g aliases per key\n", s.extrapolated_alias_rate_32);
  std::printf("records per cell: max %llu;", (unsigned long long)s.max_records_per_cell);
  for (std::size_t k = 0; k < s.records_per_cell.size(); ++k) {
    std::printf(" %llu-%llu: %llu", 1ull << k, (2ull << k) - 1, (unsigned long long)s.records_per_cell[k]);
  }
  for (std::size_t level = 0; level < s.records_per_coarser_cell.size(); ++level) {
    std::printf("\nrecords per cell %zu level%s up:", level + 1, level == 0 ? "" : "s");
    const std::vector<std::uint64_t>& histogram = s.records_per_coarser_cell[level];
    for (std::size_t k = 0; k < histogram.size(); ++k) {
      std::printf(" %llu-%llu: %llu", 1ull << k, (2ull << k) - 1, (unsigned long long)histogram[k]);
    }
  }
  std::uint64_t resolved = 0;
  for (const std::uint64_t n : s.resolved_at_level) resolved += n;
  if (s.resolved_at_level.size() > 1 || s.records_searched > 0) {
    std::printf("\nthe resolve's fallbacks (the reference's exact map), of %llu records that read a cell:",
                (unsigned long long)resolved);
  }
  for (std::size_t k = 0; k < s.resolved_at_level.size() && s.resolved_at_level.size() > 1; ++k) {
    std::printf(" %zu up: %llu (%.2f%%)", k, (unsigned long long)s.resolved_at_level[k],
                resolved ? 100.0 * double(s.resolved_at_level[k]) / double(resolved) : 0.0);
  }
  if (s.records_searched > 0) {
    std::printf(" searched: %llu (%.2f%%), %.2f neighbour cells each", (unsigned long long)s.records_searched,
                resolved ? 100.0 * double(s.records_searched) / double(resolved) : 0.0,
                double(s.neighbours_read) / double(s.records_searched));
  }
  if (s.jitter.empty()) {
    std::printf("\njitter tests: none (the keys are not hpsf's)\n");
  } else {
    std::printf("\njitter tests (each at %.3g):\n", s.jitter_alpha);
  }
  for (const JitterVerdict& v : s.jitter) {
    std::printf("  %-13s %s%s\n", ToString(v.test), v.chi_square.ToString().c_str(),
                v.chi_square.p_value <= s.jitter_alpha ? "   REJECTED" : "");
  }
  std::printf("%s\n", s.ExceedsTheory() ? "WARN: a measured rate exceeds its theory" : "every rate within its theory");
}

bool IsCapture(const std::string& input) { return std::filesystem::path(input).extension() == ".hpsfc"; }

// --second-moments: the variance of the exact map's cells.
void PrintCellVariance(const CellVarianceSummary& v) {
  std::printf(
      "cell variance (cells of 2+ samples, the exact map's): %llu cells, %llu resolved (above their rounding "
      "bound); median %.3g, 90%% %.3g, max %.3g; median relative error of a cell's mean %.3g\n ",
      (unsigned long long)v.cells, (unsigned long long)v.resolved, v.median_variance, v.p90_variance, v.max_variance,
      v.median_relative_error);
  for (std::size_t k = 0; k < v.decades.size(); ++k) {
    if (v.decades[k] == 0) continue;
    std::printf(" 1e%d: %llu", CellVarianceSummary::kLowestDecade + int(k), (unsigned long long)v.decades[k]);
  }
  std::printf("\n");
}

void PrintReport(const TableStatistics& s, const StatsOptions& o, const FilterConfig& config, double seconds,
                 const std::optional<CellVarianceSummary>& variance = std::nullopt) {
  if (o.json) {
    nlohmann::json report = s.ToJson();
    if (variance) report["cell_variance"] = variance->ToJson();
    report["version"] = 1;
    report["command"] = "stats";
    report["input"] = o.input;
    report["config"] = ToJson(config);
    report["seconds"] = seconds;
    std::cout << report.dump(2) << "\n";
  } else {
    PrintText(s, o.input);
    if (variance) PrintCellVariance(*variance);
  }
}

// A team's keys from a capture (docs/reference/capture-format.md): its own home slots and identities against
// uniform hashing, under the table its declaration declares. Keys that fail level 1 (a home slot outside the table,
// the empty marker as identity) cannot be inserted: exit 2 naming them, as hpsf judge would.
int RunOnCapture(const StatsOptions& o, bool options_only) {
  if (!o.given.empty()) {
    throw ConfigError(o.given.front(), o.input + " is a capture: its table is its declaration's, its keys its own");
  }
  if (options_only) return kExitOk;
  const Capture capture = ReadCapture(o.input);
  FilterConfig config;
  ApplyTableDeclarationText(capture.declaration, o.input + ": its declaration", config);
  const CrosscheckReport judged = JudgeCapture(capture, config);
  const LevelVerdict& keys = judged.levels.front();
  if (!keys.passed) {
    std::cerr << "hpsf: " << o.input << ": the keys fail level 1, so no statistics of them hold:\n";
    for (const std::string& f : keys.failures) std::cerr << "  " << f << "\n";
    return kExitCheckFailed;
  }
  const auto start = std::chrono::steady_clock::now();
  const TableStatistics s = MeasureGivenKeyStatistics(capture.record_count(), CapturedKeys(capture), config);
  PrintReport(s, o, config, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return s.ExceedsTheory() ? kExitWarn : kExitOk;
}

int Run(StatsOptions& o, bool options_only) {
  if (IsCapture(o.input)) return RunOnCapture(o, options_only);
  const FilterConfig config = ResolveFilterConfig(o.filter);
  ResolveTraceOptions(o.input, o.size, o.trace, config.seed);
  if (options_only) return kExitOk;
  const RecordBatch batch = LoadOrTraceBatch(o.input, o.trace);
  const auto start = std::chrono::steady_clock::now();
  const float footprint = FootprintScale(config.filter_width_px, batch.fov_y_radians, batch.height);
  const KeyParams params = MakeKeyParams(config, footprint, std::uint32_t(batch.records.size()));
  const std::vector<KeyResult> keys = ComputeKeys(batch.records, params);
  TableStatistics s = MeasureTableStatistics(batch.records, keys, config);
  s.records_per_coarser_cell = RecordsPerCoarserCell(keys, params, config.levels);
  std::optional<CellVarianceSummary> variance;
  if (config.levels > 1 || config.neighbour_search || config.second_moments) {
    const FilterResult exact = ReferenceFilter(batch, config);
    s.resolved_at_level = exact.stats.resolved_at_level;
    s.records_searched = exact.stats.records_searched;
    s.neighbours_read = exact.stats.neighbours_read;
    if (config.second_moments) variance = SummarizeCellVariance(exact, config.accumulation);
  }
  PrintReport(s, o, config, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), variance);
  return s.ExceedsTheory() ? kExitWarn : kExitOk;
}

}  // namespace

void AddStatsCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<StatsOptions>();
  CLI::App* c = app.add_subcommand("stats",
                                   "The figures that size a table for a scene: load, probes, failures, "
                                   "aliases, records per cell, jitter; each beside its theory");
  c->add_option("input", o->input,
                "A scene (built-in name or file) to trace, a recorded batch FILE.hpsfv, or a capture FILE.hpsfc of a "
                "team's own keys (docs/reference/capture-format.md)")
      ->required();
  c->add_option("--size", o->size, "Traced image size WIDTHxHEIGHT")->capture_default_str();
  c->add_option("--spp", o->trace.samples_per_pixel, "Samples per pixel")->capture_default_str();
  c->add_option("--max-depth", o->trace.max_depth,
                "Surface vertices per path, the series truncated after the last one's emission; -1: unbounded")
      ->capture_default_str();
  c->add_option("--filter-bounce", o->trace.filter_bounce, "Which diffuse vertex is filtered")->capture_default_str();
  c->add_flag("--json", o->json, "Print the versioned report as JSON");
  AddFilterOptions(*c, o->filter);
  c->callback([o, c, &context] {
    o->given.clear();
    for (const CLI::Option* option : c->get_options()) {
      if (option->count() == 0 || option->get_positional() || option->get_name() == "--json") continue;
      if (option->get_name() == "--help") continue;
      o->given.push_back(option->get_name());
    }
    context.exit_code = Run(*o, context.options_only);
  });
}

}  // namespace hpsf
