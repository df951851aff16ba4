#include "tools/hpsf/diff_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "core/error.h"
#include "tools/hpsf/channel_image_file.h"
#include "tools/hpsf/heatmap.h"
#include "tools/hpsf/html_report.h"
#include "tools/hpsf/seconds_since.h"
#include "verifier/metrics/image_comparison.h"
#include "verifier/metrics/statistical_compare.h"

namespace hpsf {
namespace {

struct DiffOptions {
  std::string a, b;
  std::string metric = "max";
  std::optional<double> warn, fail;
  double percentile = 99.0;
  double pixel_threshold = 1e-3;
  std::string heatmap;
  std::string html;
  bool ssim = false;
  bool statistical = false;
  double alpha = 0.01;
  bool json = false;
};

// --fail and --warn default only for the default metric (max: any difference warns, above 1e-6 fails); every
// other metric has its own scale, so its --fail must be given, and --warn defaults to it (no warning band).
DiffThresholds ResolveThresholds(const DiffOptions& o) {
  DiffThresholds t;
  t.metric = ParseDiffMetric(o.metric);
  if (t.metric != DiffMetric::kMaxAbs) {
    if (!o.fail) throw ConfigError("--fail", "give the threshold for --metric " + o.metric);
    t.fail = *o.fail;
    t.warn = o.warn.value_or(t.fail);
  } else {
    t.fail = o.fail.value_or(t.fail);
    t.warn = o.warn.value_or(std::min(t.warn, t.fail));
  }
  const bool higher = HigherIsBetter(t.metric);
  if (higher ? t.warn < t.fail : t.warn > t.fail) {
    throw ConfigError("--warn", "must not be " + std::string(higher ? "below" : "above") + " --fail");
  }
  return t;
}

void PrintText(const DiffOptions& o, const ChannelImage& a, const ImageComparison& c) {
  const ImageMetrics& m = c.metrics;
  std::string channels;
  for (const std::string& name : a.channels) channels += (channels.empty() ? "" : ",") + name;
  std::printf("hpsf diff %s (A) against %s (B): %dx%d [%s]\n", o.a.c_str(), o.b.c_str(), a.width, a.height,
              channels.c_str());
  std::printf("  rmse %.6g  mse %.6g  relmse %.6g  psnr %.6g dB", m.rmse, m.mse, m.relmse, m.psnr);
  if (c.ssim) std::printf("  ssim %.6g", *c.ssim);
  std::printf("\n");
  std::printf("  |A-B| mean %.6g  max %.6g at (%d, %d, %s)  p%g %.6g  pixels over %g: %.4g%%\n", m.mean_abs, m.max_abs,
              m.max_x, m.max_y, m.max_channel.c_str(), m.percentile_rank, m.percentile, m.pixel_threshold,
              100.0 * m.fraction_over);
  if (m.nonfinite_mismatches > 0) {
    std::printf("  %llu values are not finite in one image and differ in the other\n",
                (unsigned long long)m.nonfinite_mismatches);
  }
  if (c.metadata.empty()) std::printf("  metadata: the same\n");
  for (const MetadataDifference& d : c.metadata) std::printf("  metadata differs: %s\n", d.ToString().c_str());
  std::printf("%s\n", c.Explanation().c_str());
}

void Run(const DiffOptions& o, CommandContext& context) {
  const DiffThresholds thresholds = ResolveThresholds(o);
  if (context.options_only) return;
  const auto read_start = std::chrono::steady_clock::now();
  const ChannelImage a = ReadChannelImage(o.a);
  const ChannelImage b = ReadChannelImage(o.b);
  const double read_seconds = SecondsSince(read_start);
  ComparisonOptions options;
  options.thresholds = thresholds;
  options.metrics.percentile = o.percentile;
  options.metrics.pixel_threshold = o.pixel_threshold;
  options.ssim = o.ssim;
  // Everything that can refuse the input runs before the first file is written.
  ImageComparison comparison = CompareImages(a, b, options);
  std::optional<StatisticalComparison> statistical;
  double statistical_seconds = 0.0;
  if (o.statistical) {
    const auto statistical_start = std::chrono::steady_clock::now();
    const NoisyImage noisy_a = ToNoisyImage(a);  // A's missing channel is named first
    const NoisyImage noisy_b = ToNoisyImage(b);
    statistical = CompareStatistically(noisy_a, noisy_b, o.alpha);
    statistical_seconds = SecondsSince(statistical_start);
    comparison.verdict = statistical->consistent ? DiffVerdict::kPass : DiffVerdict::kFail;
    comparison.judged_by = statistical->ToString();
  }
  std::optional<Rgb8Image> heatmap;
  if (!o.heatmap.empty()) heatmap = RenderHeatmap(a, b);
  // The report is made in memory before any file is written, so that a failure leaves no heatmap behind either.
  std::string html;
  double html_seconds = 0.0;
  if (!o.html.empty()) {
    const auto html_start = std::chrono::steady_clock::now();
    ReportEntry entry{o.a + " against " + o.b, &a, &b, o.a, o.b, comparison, std::nullopt};
    if (statistical) entry.extra = ToJson(*statistical);
    const auto name = [](const std::string& path) { return std::filesystem::path(path).filename().string(); };
    html = RenderHtmlReport("hpsf diff " + name(o.a) + " against " + name(o.b), {entry});
    html_seconds = SecondsSince(html_start);
  }
  if (heatmap) WritePng(o.heatmap, *heatmap);
  if (!o.html.empty()) {
    const auto write_start = std::chrono::steady_clock::now();
    try {
      WriteHtmlReport(o.html, html);
    } catch (const InputError&) {
      std::error_code ignored;  // all or nothing: the heatmap goes too
      if (heatmap) std::filesystem::remove(o.heatmap, ignored);
      throw;
    }
    html_seconds += SecondsSince(write_start);
  }
  if (o.json) {
    nlohmann::json report = ToJson(comparison);
    report["hpsf_report"] = "diff";
    report["version"] = 1;
    report["a"] = o.a;
    report["b"] = o.b;
    report["size"] = {a.width, a.height};
    report["channels"] = a.channels;
    report["timings"]["read_s"] = read_seconds;
    if (statistical) {
      report["statistical"] = ToJson(*statistical);
      report["timings"]["statistical_s"] = statistical_seconds;
    }
    if (!o.heatmap.empty()) report["outputs"]["heatmap"] = o.heatmap;
    if (!o.html.empty()) {
      report["outputs"]["html"] = o.html;
      report["timings"]["html_s"] = html_seconds;
    }
    std::cout << report.dump(2) << "\n";
  } else {
    PrintText(o, a, comparison);
    if (!o.heatmap.empty()) std::printf("wrote %s\n", o.heatmap.c_str());
    if (!o.html.empty()) std::printf("wrote %s (%.2f s)\n", o.html.c_str(), html_seconds);
  }
  context.exit_code = ExitCode(comparison.verdict);
}

}  // namespace

void AddDiffCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<DiffOptions>();
  CLI::App* c = app.add_subcommand(
      "diff",
      "Compare a test image A with a reference B. FAIL (2) when --metric is worse than --fail or a non-finite value "
      "differs; else WARN (1) when worse than --warn; else PASS (0). Worse is greater, smaller for psnr and ssim. "
      "Bad input: 3");
  c->add_option("a", o->a, "The test image (EXR)")->required();
  c->add_option("b", o->b, "The reference image (EXR)")->required();
  c->add_option("--metric", o->metric, "mse, rmse, relmse, psnr, mean, max, percentile, fraction or ssim")
      ->capture_default_str();
  c->add_option("--warn", o->warn, "Warning threshold (max: default 0, any difference warns)");
  c->add_option("--fail", o->fail, "Failure threshold (max: default 1e-6; required for other metrics)");
  c->add_option("--percentile", o->percentile, "Which percentile of |A-B| to report, in (0, 100]")
      ->capture_default_str()
      ->check(CLI::Range(1e-9, 100.0));
  c->add_option("--pixel-threshold", o->pixel_threshold, "A pixel is over it when its largest |A-B| exceeds it")
      ->capture_default_str();
  c->add_option("--heatmap", o->heatmap, "Write the error heatmap (PNG) here");
  c->add_option("--html", o->html,
                "Write a self-contained HTML report here: A, B and the heatmap, a wipe, an exposure control, the "
                "metrics and the metadata");
  c->add_flag("--ssim", o->ssim, "Also compute SSIM (slow: 2.7 s at 1080p); implied by --metric ssim");
  c->add_flag("--statistical", o->statistical,
              "Judge by Welch t-tests of 8x8 tiles and of the image mean instead of --metric (both images rendered "
              "with --variance, 4 spp or more): FAIL when the difference is not consistent with their noise");
  c->add_option("--alpha", o->alpha, "--statistical: the probability of failing two consistent renders")
      ->capture_default_str()
      ->check(CLI::Range(1e-12, 0.5));
  c->add_flag("--json", o->json, "Print the report as JSON");
  c->callback([o, &context] { Run(*o, context); });
}

}  // namespace hpsf
