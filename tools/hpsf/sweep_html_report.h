// The HTML page of `hpsf sweep` (OUT/sweep.html): the Pareto plot and the bias and variance against
// filter width as uPlot charts (embedded, report_assets/vendor/), and a table of every configuration. Self-contained:
// the page loads nothing.
#ifndef HPSF_TOOLS_HPSF_SWEEP_HTML_REPORT_H
#define HPSF_TOOLS_HPSF_SWEEP_HTML_REPORT_H

#include <string>

#include <nlohmann/json.hpp>

namespace hpsf {

// configurations: the finished configurations' results, as sweep.json lists them (id, method, backend, spp, filter,
// total_s, relmse, ssim, rel_bias2, rel_variance, frontier, pt_relmse_at_equal_time). reference: what the errors are
// measured against.
std::string RenderSweepHtml(const std::string& scene, const nlohmann::json& configurations,
                            const std::string& reference);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_SWEEP_HTML_REPORT_H
