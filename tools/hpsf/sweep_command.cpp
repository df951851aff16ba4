#include "tools/hpsf/sweep_command.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/hashed_run.h"
#include "reference/radius_search_filter.h"
#include "reference/reference_filter.h"
#include "reference/screen_space_filter.h"
#include "tools/hpsf/backend_options.h"
#include "tools/hpsf/bias_variance_plot.h"
#include "tools/hpsf/channel_image_file.h"
#include "tools/hpsf/filter_options.h"
#include "tools/hpsf/heatmap.h"
#include "tools/hpsf/html_report.h"
#include "tools/hpsf/image_size.h"
#include "tools/hpsf/pareto_plot.h"
#include "tools/hpsf/reference_cache.h"
#include "tools/hpsf/seconds_since.h"
#include "tools/hpsf/sweep_grid.h"
#include "tools/hpsf/sweep_html_report.h"
#include "tracer/scene_file.h"
#include "verifier/gate/gate_file.h"
#include "verifier/metrics/channel_image.h"
#include "verifier/metrics/error_split.h"
#include "verifier/metrics/fireflies.h"
#include "verifier/metrics/image_metrics.h"
#include "verifier/metrics/pareto.h"
#include "verifier/metrics/ssim.h"

namespace hpsf {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// The seed of the converged image: apart from the sweep's seeds 1..K, so that no image is measured against its own
// samples.
constexpr std::uint32_t kReferenceSeed = 1000003;

struct SweepOptions {
  std::string scene;
  std::string grid;
  std::string size = "128x128";
  std::uint32_t seeds = 3;
  std::uint32_t reference_spp = 1024;
  int max_depth = 8;
  std::string cache;
  std::string shard = "1/1";
  std::string out = "hpsf-sweep";
  bool json = false;
};

FilterConfig FilterConfigOf(const SweepConfig& c) {
  CLI::App app;
  FilterOptions options;
  AddFilterOptions(app, options);
  std::vector<std::string> words = {"sweep"};
  const std::vector<std::string> arguments = c.FilterArguments();
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<const char*> argv;
  for (const std::string& w : words) argv.push_back(w.c_str());
  try {
    app.parse(int(argv.size()), argv.data());
    return ResolveFilterConfig(options);
  } catch (const CLI::ParseError& e) {
    throw ConfigError("--grid", c.id + ": " + e.what());
  } catch (const InputError& e) {
    throw ConfigError("--grid", c.id + ": " + e.what());
  }
}

Image ColourOf(const ChannelImage& c, const std::string& prefix) {
  Image image(std::uint32_t(c.width), std::uint32_t(c.height));
  const int r = c.ChannelIndex(prefix + "R"), g = c.ChannelIndex(prefix + "G"), b = c.ChannelIndex(prefix + "B");
  if (r < 0 || g < 0 || b < 0) throw InputError(c.path + ": no " + prefix + "R, G, B channels");
  for (std::size_t p = 0; p < image.pixels.size(); ++p) {
    image.pixels[p] = glm::vec3(c.At(p, std::size_t(r)), c.At(p, std::size_t(g)), c.At(p, std::size_t(b)));
  }
  return image;
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

struct Traced {
  RecordBatch batch;
  double seconds = 0.0;
};

// One seed of one configuration: its image, the filter's time and phases, the table's failures.
struct SeedRun {
  Image image;
  double filter_s = 0.0;
  json phases = json::object();
  std::uint64_t probe_failures = 0, aliased_slots = 0;
};

class Runner {
 public:
  SeedRun Run(const SweepConfig& c, const FilterConfig& config, const RecordBatch& batch) {
    SeedRun run;
    const auto start = Clock::now();
    if (c.method == "pt") {
      run.image = UnfilteredImage(batch);
    } else if (c.method == "radius") {
      run.image = RadiusSearchFilter(batch, config).image;
    } else if (c.method == "screen") {
      run.image = ScreenSpaceFilter(batch, config).image;
    } else {
      BackendInstance& backend = BackendFor(c.backend);
      backend.backend->Reset();
      run.image = backend.backend->FilterFrame(batch, config);
      run.filter_s = SecondsSince(start);
      if (backend.info->hashed) {  // the reference times none of its phases
        const FrameTimings t = backend.backend->LastFrameTimings();
        if (t.keys_ms) run.phases["key_s"] = *t.keys_ms / 1e3;  // Vulkan computes keys in its accumulate pass
        run.phases["accumulate_s"] = t.accumulate_ms / 1e3;
        run.phases["resolve_s"] = t.resolve_ms / 1e3;
        if (t.transfer_ms) run.phases["transfer_s"] = *t.transfer_ms / 1e3;
      }
      if (const HashedRun* hashed = backend.backend->LastHashedRun()) {
        run.probe_failures = hashed->probe_failures;
        const std::vector<bool> aliased = AliasedSlots(*hashed);
        run.aliased_slots = std::uint64_t(std::count(aliased.begin(), aliased.end(), true));
      }
      return run;
    }
    run.filter_s = SecondsSince(start);
    return run;
  }

 private:
  BackendInstance& BackendFor(const std::string& name) {
    auto it = backends_.find(name);
    if (it == backends_.end()) it = backends_.emplace(name, MakeBackend(name, EmulatorOptions{})).first;
    return it->second;
  }
  std::map<std::string, BackendInstance> backends_;
};

// Everything a configuration's figures depend on: a kept result is reused only when this matches.
std::string Description(const SweepConfig& c, const SweepOptions& o, const std::string& reference) {
  return c.id + "; " + o.size + ", seeds 1.." + std::to_string(o.seeds) + ", max depth " + std::to_string(o.max_depth) +
         "; against " + reference;
}

std::string ConfigFile(const fs::path& out, std::size_t index, const SweepConfig& c) {
  std::string name = c.id;
  for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '.' ? ch : '_';
  char prefix[16];
  std::snprintf(prefix, sizeof prefix, "%04zu-", index);
  return (out / "configs" / (prefix + name + ".json")).string();
}

json MeasureConfig(const SweepConfig& c, const FilterConfig& config, const std::vector<Traced>& traced,
                   const Image& reference, const Image& reference_variance, std::uint32_t reference_spp,
                   Runner& runner) {
  const ChannelImage reference_channels = ColourChannels(reference);
  std::vector<Image> images;
  std::vector<double> trace_s, filter_s, mse, relmse, ssim, fireflies;
  std::map<std::string, std::vector<double>> phases;
  std::uint64_t probe_failures = 0, aliased = 0;
  for (std::size_t k = 0; k < traced.size(); ++k) {
    FilterConfig seeded = config;
    seeded.seed = std::uint32_t(k + 1);
    SeedRun run = runner.Run(c, seeded, traced[k].batch);
    const ChannelImage channels = ColourChannels(run.image);
    const ImageMetrics metrics = ComputeMetrics(channels, reference_channels);
    trace_s.push_back(traced[k].seconds);
    filter_s.push_back(run.filter_s);
    mse.push_back(metrics.mse);
    relmse.push_back(metrics.relmse);
    ssim.push_back(SrgbSsim(channels, reference_channels));
    fireflies.push_back(double(CountFireflies(run.image, c.spp, reference, reference_variance, reference_spp)));
    for (auto it = run.phases.begin(); it != run.phases.end(); ++it) phases[it.key()].push_back(it.value());
    probe_failures += run.probe_failures;
    aliased += run.aliased_slots;
    images.push_back(std::move(run.image));
  }
  const auto mean = [](const std::vector<double>& v) {
    double sum = 0.0;
    for (const double x : v) sum += x;
    return sum / double(v.size());
  };
  json result = {{"id", c.id},
                 {"method", c.method},
                 {"backend", c.backend},
                 {"spp", c.spp},
                 {"filter", json::object()},
                 {"seeds", traced.size()},
                 {"trace_s", Median(trace_s)},
                 {"filter_s", Median(filter_s)},
                 {"total_s", Median(trace_s) + Median(filter_s)},
                 {"mse", mean(mse)},
                 {"relmse", mean(relmse)},
                 {"ssim", mean(ssim)},
                 {"fireflies", mean(fireflies)},
                 {"probe_failures", probe_failures},
                 {"aliased_slots", aliased}};
  for (const auto& [name, value] : c.filter) result["filter"][name] = value;
  for (const auto& [name, values] : phases) result["phases"][name] = Median(values);
  if (images.size() >= 2) {
    const ErrorSplit split = SplitError(images, reference, &reference_variance);
    result["bias2"] = split.bias2;
    result["bias2_standard_error"] = split.bias2_standard_error;
    result["mean_error"] = split.mean_error;
    result["mean_error_standard_error"] = split.mean_error_standard_error;
    result["variance"] = split.variance;
    result["reference_variance"] = split.reference_variance;
    result["rel_bias2"] = split.rel_bias2;
    result["rel_variance"] = split.rel_variance;
    result["rel_reference_variance"] = split.rel_reference_variance;
  }
  return result;
}

// Each finished configuration's place against time: whether it is on its method's frontier of relMSE against total
// time (hpsf per backend), and the relMSE plain path tracing's frontier reaches in the same time, the line to beat
// (null when no pt configuration is that fast); and the plot of them all, OUT/pareto.png.
void MarkFrontiers(std::vector<json>& results, const std::string& scene, const fs::path& out) {
  std::vector<TimedError> points;
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (results[i].is_null()) continue;
    const json& r = results[i];
    const std::string backend = r["backend"].get<std::string>();
    points.push_back({r["method"].get<std::string>() + (backend == "-" ? "" : "/" + backend),
                      r["total_s"].get<double>(), r["relmse"].get<double>()});
    at.push_back(i);
  }
  const std::vector<bool> frontier = ParetoFrontier(points);
  for (std::size_t k = 0; k < points.size(); ++k) {
    json& r = results[at[k]];
    r["frontier"] = bool(frontier[k]);
    const double pt = FrontierErrorAt(points, frontier, "pt", points[k].seconds);
    r["pt_relmse_at_equal_time"] = pt < 0.0 ? json() : json(pt);
  }
  if (!points.empty()) WritePng((out / "pareto.png").string(), RenderParetoPlot(scene, points, frontier));
}

// The second plot, OUT/bias-variance.png: relMSE's bias^2 and variance against filter width for each group of
// configurations that differ only in their filter width, when the grid sweeps two widths or more.
void PlotBiasAgainstWidth(const std::vector<json>& results, const std::string& scene, const fs::path& out) {
  std::map<std::string, WidthSeries> groups;
  std::vector<std::string> order;
  for (const json& r : results) {
    if (r.is_null() || !r["filter"].contains("filter-width")) continue;
    std::string label = r["id"].get<std::string>();
    const std::string token = "filter-width=" + r["filter"]["filter-width"].get<std::string>();
    const std::size_t at = label.find(token);
    if (at != std::string::npos) label.erase(at > 0 ? at - 1 : at, token.size() + (at > 0 ? 1 : 0));
    auto [it, inserted] = groups.try_emplace(label);
    if (inserted) order.push_back(label);
    WidthSeries& s = it->second;
    s.label = label;
    s.method = r["method"].get<std::string>();
    s.widths.push_back(std::stod(r["filter"]["filter-width"].get<std::string>()));
    s.bias2.push_back(r.value("rel_bias2", 0.0));
    s.variance.push_back(r.value("rel_variance", 0.0));
  }
  std::vector<WidthSeries> series;
  for (const std::string& label : order) {
    const WidthSeries& s = groups[label];
    if (s.widths.size() < 2) continue;
    // In increasing width: a grid may list its widths in any order.
    std::vector<std::array<double, 3>> points;
    for (std::size_t k = 0; k < s.widths.size(); ++k) points.push_back({s.widths[k], s.bias2[k], s.variance[k]});
    std::sort(points.begin(), points.end());
    WidthSeries& sorted = series.emplace_back(WidthSeries{s.label, s.method, {}, {}, {}});
    for (const auto& [width, bias2, variance] : points) {
      sorted.widths.push_back(width);
      sorted.bias2.push_back(bias2);
      sorted.variance.push_back(variance);
    }
  }
  if (!series.empty()) WritePng((out / "bias-variance.png").string(), RenderBiasVariancePlot(scene, series));
}

std::string CsvField(const json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

void WriteSummaries(const fs::path& out, const std::vector<SweepConfig>& configs, const std::vector<json>& results,
                    const std::vector<GridAxis>& axes, const std::string& scene, const std::string& reference) {
  std::vector<std::string> filter_axes;
  for (const GridAxis& a : axes) {
    if (a.name != "spp" && a.name != "method" && a.name != "backend") filter_axes.push_back(a.name);
  }
  std::ofstream csv(out / "sweep.csv");
  csv << "id,method,backend,spp";
  for (const std::string& a : filter_axes) csv << "," << a;
  const std::vector<std::string> figures = {"seeds",
                                            "trace_s",
                                            "filter_s",
                                            "total_s",
                                            "mse",
                                            "relmse",
                                            "ssim",
                                            "fireflies",
                                            "bias2",
                                            "bias2_standard_error",
                                            "mean_error",
                                            "mean_error_standard_error",
                                            "variance",
                                            "reference_variance",
                                            "rel_bias2",
                                            "rel_variance",
                                            "rel_reference_variance",
                                            "probe_failures",
                                            "aliased_slots",
                                            "frontier",
                                            "pt_relmse_at_equal_time"};
  for (const std::string& f : figures) csv << "," << f;
  csv << "\n";
  json all = json::array();
  for (std::size_t i = 0; i < configs.size(); ++i) {
    if (results[i].is_null()) continue;
    const json& r = results[i];
    csv << '"' << r["id"].get<std::string>() << "\"," << CsvField(r["method"]) << "," << CsvField(r["backend"]) << ","
        << CsvField(r["spp"]);
    for (const std::string& a : filter_axes) csv << "," << CsvField(r["filter"].value(a, json()));
    for (const std::string& f : figures) csv << "," << CsvField(r.value(f, json()));
    csv << "\n";
    all.push_back(r);
  }
  std::ofstream(out / "sweep.json") << json{{"version", 1}, {"command", "sweep"}, {"configurations", all}}.dump(2)
                                    << "\n";
  WriteHtmlReport((out / "sweep.html").string(), RenderSweepHtml(scene, all, reference));
}

int Run(SweepOptions& o, bool options_only) {
  ReferenceRequest reference_request;
  ParseSize(o.size, reference_request.trace);
  reference_request.trace.seed = kReferenceSeed;
  reference_request.trace.max_depth = o.max_depth;
  reference_request.samples_per_pixel = o.reference_spp;
  reference_request.Validate();
  if (o.seeds == 0) throw ConfigError("--seeds", "must be at least 1");
  const std::vector<GridAxis> axes = ParseGrid(o.grid);
  for (const GridAxis& a : axes) {
    if (a.name == "seed") throw ConfigError("--grid", "seed is not an axis: --seeds K runs seeds 1..K");
  }
  const std::vector<SweepConfig> configs = ExpandGrid(axes);
  std::vector<FilterConfig> filter_configs;
  for (const SweepConfig& c : configs) filter_configs.push_back(FilterConfigOf(c));
  const auto [shard, shards] = ParseShard(o.shard);
  if (options_only) return kExitOk;

  const Scene scene = LoadScene(o.scene);
  const bool terminal = isatty(STDERR_FILENO) && !o.json;
  const ReferenceImage reference =
      GetReferenceImage(scene, o.scene, reference_request, o.cache.empty() ? DefaultReferenceCache() : o.cache, false,
                        [&](std::uint32_t done, std::uint32_t total) {
                          if (terminal)
                            std::fprintf(stderr, "\rsweep: the converged image, pass %u of %u", done, total);
                        });
  const ChannelImage converged = ReadChannelImage(reference.entry.image);
  const Image reference_image = ColourOf(converged, ""), reference_variance = ColourOf(converged, "variance.");
  const fs::path out = o.out;
  fs::create_directories(out / "configs");

  // Run in order of spp, so that each spp's K batches are traced once; report in grid order.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    if (i % shards == shard - 1) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return configs[a].spp < configs[b].spp; });
  std::vector<json> results(configs.size());
  Runner runner;
  std::vector<Traced> traced;
  std::uint32_t traced_spp = 0;
  std::size_t done = 0, resumed = 0;
  const auto start = Clock::now();
  for (const std::size_t i : order) {
    const SweepConfig& c = configs[i];
    const std::string path = ConfigFile(out, i, c);
    const std::string description = Description(c, o, reference.description);
    if (std::ifstream in(path); in) {
      json kept = json::parse(in, nullptr, false);
      if (!kept.is_discarded() && kept.value("description", "") == description) {
        results[i] = kept["result"];
        ++done;
        ++resumed;
        continue;
      }
    }
    if (traced_spp != c.spp) {
      traced.clear();
      for (std::uint32_t k = 1; k <= o.seeds; ++k) {
        TraceOptions trace = reference_request.trace;
        trace.samples_per_pixel = c.spp;
        trace.seed = k;
        const auto trace_start = Clock::now();
        RecordBatch batch = TraceRecords(scene, trace).batch;
        traced.push_back({std::move(batch), SecondsSince(trace_start)});
      }
      traced_spp = c.spp;
    }
    results[i] =
        MeasureConfig(c, filter_configs[i], traced, reference_image, reference_variance, o.reference_spp, runner);
    std::ofstream(path) << json{{"description", description}, {"result", results[i]}}.dump(2) << "\n";
    ++done;
    if (terminal) {
      const double elapsed = SecondsSince(start);
      const double eta = elapsed / double(done - resumed) * double(order.size() - done);
      std::fprintf(stderr, "\rsweep: %zu of %zu configurations, %.0f s, about %.0f s to go   ", done, order.size(),
                   elapsed, eta);
    }
  }
  if (terminal) std::fprintf(stderr, "\r%78s\r", "");
  // Every configuration kept in OUT, this shard's or another's.
  for (std::size_t i = 0; i < configs.size(); ++i) {
    if (!results[i].is_null()) continue;
    if (std::ifstream in(ConfigFile(out, i, configs[i])); in) {
      const json kept = json::parse(in, nullptr, false);
      if (!kept.is_discarded() && kept.value("description", "") == Description(configs[i], o, reference.description)) {
        results[i] = kept["result"];
      }
    }
  }
  MarkFrontiers(results, o.scene, out);
  // One seed measures the error but cannot split it into bias^2 and variance: no plot, and none left from before.
  if (o.seeds >= 2) {
    PlotBiasAgainstWidth(results, o.scene, out);
  } else {
    std::error_code ignored;
    fs::remove(out / "bias-variance.png", ignored);
  }
  WriteSummaries(out, configs, results, axes, o.scene,
                 "a converged image of " + std::to_string(o.reference_spp) + " spp (" + reference.entry.image + ")");
  std::size_t finished = 0;
  for (const json& r : results) finished += !r.is_null();
  if (o.json) {
    json all = json::array();
    for (const json& r : results) {
      if (!r.is_null()) all.push_back(r);
    }
    std::cout << json{{"version", 1},
                      {"command", "sweep"},
                      {"reference", reference.entry.image},
                      {"configurations", all},
                      {"run", done - resumed},
                      {"resumed", resumed},
                      {"seconds", SecondsSince(start)}}
                     .dump(2)
              << "\n";
  } else {
    std::printf("%-58s %8s %8s %9s %9s %9s %9s %7s\n", "configuration", "trace s", "filter s", "relMSE", "MSE",
                "bias^2", "variance", "SSIM");
    for (const json& r : results) {
      if (r.is_null()) continue;
      std::printf("%-58s %8.4f %8.4f %9.4g %9.4g %9.3g %9.4g %7.4f\n", r["id"].get<std::string>().c_str(),
                  r["trace_s"].get<double>(), r["filter_s"].get<double>(), r["relmse"].get<double>(),
                  r["mse"].get<double>(), r.value("bias2", 0.0), r.value("variance", 0.0), r["ssim"].get<double>());
    }
    std::printf("sweep: %zu configurations run, %zu kept from before, %zu of %zu in %s (%.1f s)\n", done - resumed,
                resumed, finished, configs.size(), (out / "sweep.csv").c_str(), SecondsSince(start));
  }
  return kExitOk;
}

}  // namespace

void AddSweepCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* c = app.add_subcommand(
      "sweep",
      "What accuracy costs in time: every configuration of a grid, traced and filtered with K seeds, timed "
      "and measured against the scene's converged image (relMSE, SSIM, bias^2 and variance)");
  c->add_option("scene", o->scene, "A built-in scene or a scene file")->required();
  c->add_option("--grid", o->grid,
                "Axes and values, e.g. \"spp=1,4; filter-width=2,4; method=pt,hpsf,radius,screen; "
                "backend=reference,emulated\" (other axes: any filter option without its dashes)")
      ->required()
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);  // a later --grid replaces an earlier one
  c->add_option("--seeds", o->seeds, "Independent seeds per configuration (1..K); 2 or more split the error")
      ->capture_default_str();
  c->add_option("--size", o->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  c->add_option("--reference-spp", o->reference_spp, "Samples per pixel of the converged image (multiple of 16)")
      ->capture_default_str();
  c->add_option("--max-depth", o->max_depth, "Surface vertices per path; -1: unbounded")->capture_default_str();
  c->add_option("--cache", o->cache, "The converged images' cache (see hpsf reference)");
  c->add_option("--shard", o->shard, "Run configurations I, I + N, ... of the grid")->capture_default_str();
  c->add_option("--out", o->out, "Where each configuration's result, sweep.csv and sweep.json go")
      ->capture_default_str();
  c->add_flag("--json", o->json, "Print the versioned report as JSON");
  c->callback([o, &context] { context.exit_code = Run(*o, context.options_only); });
}

}  // namespace hpsf
