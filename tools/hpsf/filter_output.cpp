#include "tools/hpsf/filter_output.h"

#include <chrono>
#include <cstdio>
#include <iostream>

#include "core/error.h"
#include "tools/hpsf/image_file.h"
#include "tools/hpsf/version.h"

namespace hpsf {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

nlohmann::json FilterAndWrite(const RecordBatch& batch, const FilterOptions& options, const OutputRequest& request) {
  CheckBackend(request.backend);
  const FilterConfig config = ResolveFilterConfig(options);
  nlohmann::json report;
  const auto filter_start = std::chrono::steady_clock::now();
  const BackendOutput result = RunBackend(request.backend, batch, config, request.emulator, request.defect, request.vulkan);
  const double filter_seconds = SecondsSince(filter_start);
  const Image image = options.no_filter ? UnfilteredImage(batch) : result.image;
  const int fixed_point_bits = result.reference ? result.reference->stats.fixed_point_bits : result.emulated->table.fixed_point_bits;

  const std::map<std::string, std::string> metadata = {
      {"scene", request.scene},
      {"config", config.ToString()},
      {"seed", std::to_string(config.seed)},
      {"backend", options.no_filter ? "none (unfiltered)" : request.backend},
      {"version", kHpsfVersion},
      {"F", std::to_string(fixed_point_bits)}};
  const auto write_start = std::chrono::steady_clock::now();
  const std::string preview = WriteImageFiles(request.output, image, metadata);

  report["filtered"] = !options.no_filter;
  report["backend"] = request.backend;
  report["config"] = ToJson(config);
  report["stats"] = result.stats;
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
            << ")\n";
  if (s.contains("cells")) {
    std::cout << "records " << s["records"] << ", without vertex " << s["records_without_vertex"] << ", unkeyable "
              << s["unkeyable"] << ", rejected " << s["rejected_non_finite"].get<std::uint64_t>() + s["rejected_negative"].get<std::uint64_t>()
              << ", cells " << s["cells"] << ", F " << s["fixed_point_bits"] << "\n";
  } else if (s.contains("device")) {
    std::cout << "vulkan on " << s["device"].get<std::string>() << ": slots used " << s["slots_used"] << ", probe failures "
              << s["probe_failures"] << ", F " << s["fixed_point_bits"] << (s["staged"].get<bool>() ? ", staged" : ", mapped")
              << "; ms upload " << s["timings_ms"]["upload"] << " + copy " << s["timings_ms"]["upload_copy"] << ", accumulate "
              << s["timings_ms"]["accumulate"] << ", resolve " << s["timings_ms"]["resolve"] << ", read-back copy "
              << s["timings_ms"]["read_back_copy"] << " + " << s["timings_ms"]["read_back"] << "; GB/s up "
              << s["transfers"]["upload_gb_per_s"] << ", down " << s["transfers"]["read_back_gb_per_s"] << "\n";
  } else {
    std::cout << "emulated (" << s["mode"].get<std::string>() << "): slots used " << s["slots_used"] << ", probe failures "
              << s["probe_failures"] << ", F " << s["fixed_point_bits"]
              << (s.contains("trace_hash") ? ", trace " + s["trace_hash"].get<std::string>() : std::string()) << "\n";
  }
  if (report.contains("rays_per_s")) {
    std::printf("%.3g rays/s, %.3g records/s filtered\n", report["rays_per_s"].get<double>(), report["records_per_s"].get<double>());
  }
}

}  // namespace hpsf
