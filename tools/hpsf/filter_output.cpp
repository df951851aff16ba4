#include "tools/hpsf/filter_output.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <vector>

#include "core/error.h"
#include "tools/hpsf/cell_variance_map.h"
#include "tools/hpsf/frame_soundness.h"
#include "tools/hpsf/image_file.h"
#include "tools/hpsf/seconds_since.h"
#include "tools/hpsf/version.h"
#include "verifier/metrics/cell_variance.h"
#include "verifier/metrics/pixel_variance.h"

namespace hpsf {
namespace {

// The variance from the groups whose averages the backend's resolve used: the reference's cells or a hashed
// table's slots (a probe failure or an unplaced record is past the capacity), or none without the filter.
PixelVariance EstimateVariance(const RecordBatch& batch, const Backend& backend, bool filtered) {
  if (!filtered) return EstimatePixelVariance(batch, {}, 0);
  if (const FilterResult* exact = backend.LastExactResult()) {
    return EstimatePixelVariance(batch, exact->placement, exact->cells.size());
  }
  const HashedRun& hashed = *backend.LastHashedRun();
  return EstimatePixelVariance(batch, hashed.placements, hashed.table.capacity);
}

// Each pixel holds its tile's variance, so the file keeps one size for every channel.
Image TileVarianceLayer(const PixelVariance& v) {
  Image layer(v.variance.width, v.variance.height);
  const std::uint32_t t = v.tile_size;
  for (std::uint32_t y = 0; y < layer.height; ++y) {
    for (std::uint32_t x = 0; x < layer.width; ++x) {
      layer.pixels[std::size_t(y) * layer.width + x] =
          v.tile_variance.pixels[std::size_t(y / t) * v.tile_variance.width + x / t];
    }
  }
  return layer;
}

// Every digit of a double, so the statistical comparison reads back exactly what was estimated.
std::string Digits(const glm::dvec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "%.17g %.17g %.17g", v.x, v.y, v.z);
  return text;
}

}  // namespace

nlohmann::json FilterAndWrite(BackendInstance& backend, const RecordBatch& batch, const FilterConfig& config,
                              const FilterOptions& options, const OutputRequest& request) {
  CheckVarianceSamples(options, batch.samples_per_pixel, "the batch of " + request.scene);
  nlohmann::json report;
  const auto filter_start = std::chrono::steady_clock::now();
  const Image& filtered = backend.backend->FilterFrame(batch, config);
  const double filter_seconds = SecondsSince(filter_start);
  RequireSoundFrame(*backend.backend, filtered, config);
  const Image image = options.no_filter ? UnfilteredImage(batch) : filtered;
  const FilterResult* exact = backend.backend->LastExactResult();
  const int fixed_point_bits =
      exact ? exact->stats.fixed_point_bits : backend.backend->LastHashedRun()->table.fixed_point_bits;

  std::map<std::string, std::string> metadata = {{"scene", request.scene},
                                                 {"config", config.ToString()},
                                                 {"seed", std::to_string(config.seed)},
                                                 {"backend", options.no_filter ? "none (unfiltered)" : request.backend},
                                                 {"version", kHpsfVersion},
                                                 {"F", std::to_string(fixed_point_bits)}};
  std::optional<PixelVariance> variance;
  if (options.variance) {
    const auto variance_start = std::chrono::steady_clock::now();
    variance = EstimateVariance(batch, *backend.backend, !options.no_filter);
    report["timings"]["variance_s"] = SecondsSince(variance_start);
    metadata["mean_variance"] = Digits(variance->mean_variance);
    metadata["spp"] = std::to_string(batch.samples_per_pixel);
    metadata["variance_tile"] = std::to_string(variance->tile_size);
    report["mean_variance"] = {variance->mean_variance.x, variance->mean_variance.y, variance->mean_variance.z};
  }
  const auto write_start = std::chrono::steady_clock::now();
  const Image tile_variance = variance ? TileVarianceLayer(*variance) : Image();
  std::vector<ImageLayer> layers;
  if (variance) layers = {{"variance", &variance->variance}, {"tile_variance", &tile_variance}};
  // With second moments, the debug image of the table's variance per cell (tools/hpsf/cell_variance_map.h), made before
  // anything is written and written after the image: all or nothing.
  std::optional<Rgb8Image> variance_map;
  if (config.second_moments && !options.no_filter) {
    const std::vector<float> cell_variance = exact ? CellVariancePerPixel(batch, *exact, config.accumulation)
                                                   : CellVariancePerPixel(batch, *backend.backend->LastHashedRun());
    variance_map = RenderCellVarianceMap(cell_variance, int(batch.width), int(batch.height));
  }
  const std::string preview = WriteImageFiles(request.output, image, metadata, layers);
  if (variance_map) {
    try {
      WritePng(CellVarianceMapPath(request.output), *variance_map);
    } catch (const InputError&) {
      std::error_code ignored;
      std::filesystem::remove(request.output, ignored);
      std::filesystem::remove(preview, ignored);
      throw;
    }
    report["cell_variance_image"] = CellVarianceMapPath(request.output);
  }

  report["filtered"] = !options.no_filter;
  report["backend"] = request.backend;
  report["config"] = ToJson(config);
  report["stats"] = backend.last_frame_stats();
  report["output"] = request.output;
  report["preview"] = preview;
  report["timings"]["filter_s"] = filter_seconds;
  report["timings"]["write_s"] = SecondsSince(write_start);
  report["records_per_s"] = filter_seconds > 0.0 ? double(batch.records.size()) / filter_seconds : 0.0;
  return report;
}

void PrintReport(const nlohmann::json& report, bool as_json) {
  if (as_json) {
    std::cout << report.dump(2) << "\n";
    return;
  }
  const auto& s = report["stats"];
  std::cout << "wrote " << report["output"].get<std::string>() << " and " << report["preview"].get<std::string>()
            << " ("
            << (report["filtered"].get<bool>() ? "filtered, " + report["backend"].get<std::string>()
                                               : std::string("unfiltered"))
            << ")\n";
  if (report.contains("cell_variance_image")) {
    std::cout << "wrote " << report["cell_variance_image"].get<std::string>() << " (the variance per cell)\n";
  }
  if (s.contains("cells")) {
    std::cout << "records " << s["records"] << ", without vertex " << s["records_without_vertex"] << ", unkeyable "
              << s["unkeyable"] << ", rejected "
              << s["rejected_non_finite"].get<std::uint64_t>() + s["rejected_negative"].get<std::uint64_t>()
              << ", cells " << s["cells"] << ", F " << s["fixed_point_bits"] << "\n";
  } else if (s.contains("device")) {
    std::cout << "vulkan on " << s["device"].get<std::string>() << ": slots used " << s["slots_used"]
              << ", probe failures " << s["probe_failures"] << ", F " << s["fixed_point_bits"]
              << (s["staged"].get<bool>() ? ", staged" : ", mapped") << "; ms upload " << s["timings_ms"]["upload"]
              << " + copy " << s["timings_ms"]["upload_copy"] << ", accumulate " << s["timings_ms"]["accumulate"]
              << ", resolve " << s["timings_ms"]["resolve"] << ", read-back copy " << s["timings_ms"]["read_back_copy"]
              << " + " << s["timings_ms"]["read_back"] << "; GB/s up " << s["transfers"]["upload_gb_per_s"] << ", down "
              << s["transfers"]["read_back_gb_per_s"] << "\n";
  } else {
    std::cout << "emulated (" << s["mode"].get<std::string>() << "): slots used " << s["slots_used"]
              << ", probe failures " << s["probe_failures"] << ", F " << s["fixed_point_bits"]
              << (s.contains("trace_hash") ? ", trace " + s["trace_hash"].get<std::string>() : std::string()) << "\n";
  }
  if (report.contains("mean_variance")) {
    const auto& v = report["mean_variance"];
    std::printf("variance of the image mean: %.3g %.3g %.3g\n", v[0].get<double>(), v[1].get<double>(),
                v[2].get<double>());
  }
  if (report.contains("series")) {
    std::cout << "series: " << (report["series"]["converged"].get<bool>() ? "converged" : "not converged") << " ("
              << report["series"]["rising_frames"] << " rising frames at the end, last change "
              << report["series"]["last_relative_change"].get<double>() * 100.0 << "%)\n";
  }
  if (report.contains("rays_per_s")) {
    std::printf("%.3g rays/s, %.3g records/s filtered\n", report["rays_per_s"].get<double>(),
                report["records_per_s"].get<double>());
  }
}

}  // namespace hpsf
