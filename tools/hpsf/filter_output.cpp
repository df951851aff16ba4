#include "tools/hpsf/filter_output.h"

#include <chrono>
#include <cstdio>
#include <iostream>

#include "core/error.h"
#include "reference/reference_filter.h"
#include "tools/hpsf/image_file.h"
#include "tools/hpsf/version.h"

namespace hpsf {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void CheckBackend(const std::string& backend) {
  if (backend != "reference") {
    throw ConfigError("--backend", "'" + backend + "' is not available; this build has: reference");
  }
}

nlohmann::json FilterAndWrite(const RecordBatch& batch, const FilterOptions& options, const OutputRequest& request) {
  CheckBackend(request.backend);
  const FilterConfig config = ResolveFilterConfig(options);
  nlohmann::json report;
  const auto filter_start = std::chrono::steady_clock::now();
  FilterResult result = ReferenceFilter(batch, config);  // its stats are wanted even when not filtering
  const double filter_seconds = SecondsSince(filter_start);
  const Image image = options.no_filter ? UnfilteredImage(batch) : result.image;

  const std::map<std::string, std::string> metadata = {
      {"scene", request.scene},
      {"config", config.ToString()},
      {"seed", std::to_string(config.seed)},
      {"backend", options.no_filter ? "none (unfiltered)" : request.backend},
      {"version", kHpsfVersion},
      {"F", std::to_string(result.stats.fixed_point_bits)}};
  const auto write_start = std::chrono::steady_clock::now();
  const std::string preview = WriteImageFiles(request.output, image, metadata);

  report["filtered"] = !options.no_filter;
  report["backend"] = request.backend;
  report["config"] = ToJson(config);
  report["stats"] = ToJson(result.stats);
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
  std::cout << "wrote " << report["output"].get<std::string>() << " and " << report["preview"].get<std::string>() << " ("
            << (report["filtered"].get<bool>() ? "filtered, " + report["backend"].get<std::string>() : std::string("unfiltered"))
            << ")\n"
            << "records " << s["records"] << ", without vertex " << s["records_without_vertex"] << ", unkeyable "
            << s["unkeyable"] << ", rejected " << s["rejected_non_finite"].get<std::uint64_t>() + s["rejected_negative"].get<std::uint64_t>()
            << ", cells " << s["cells"] << ", F " << s["fixed_point_bits"] << "\n";
  if (report.contains("rays_per_s")) {
    std::printf("%.3g rays/s, %.3g records/s filtered\n", report["rays_per_s"].get<double>(), report["records_per_s"].get<double>());
  }
}

}  // namespace hpsf
