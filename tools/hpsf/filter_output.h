// The back half of `hpsf render` and `hpsf replay`: filter a frame's batch with the chosen backend (or not at all),
// write the EXR and its PNG preview, and return the report's filter part.
#ifndef HPSF_TOOLS_HPSF_FILTER_OUTPUT_H
#define HPSF_TOOLS_HPSF_FILTER_OUTPUT_H

#include <string>

#include <nlohmann/json.hpp>

#include "core/record.h"
#include "tools/hpsf/backend_options.h"
#include "tools/hpsf/filter_options.h"

namespace hpsf {

struct OutputRequest {
  std::string scene;    // name recorded in the metadata
  std::string backend;  // reference, emulated or vulkan
  std::string output;   // OUT.exr
};

// config: ResolveFilterConfig(options) with the frame set; the frame goes into the backend's table, which keeps
// the frames before it (core/backend.h).
nlohmann::json FilterAndWrite(BackendInstance& backend, const RecordBatch& batch, const FilterConfig& config,
                              const FilterOptions& options, const OutputRequest& request);

// Prints the report as JSON, or a short human summary.
void PrintReport(const nlohmann::json& report, bool as_json);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_FILTER_OUTPUT_H
