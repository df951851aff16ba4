#include "core/path_graph.h"

#include <cmath>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/number_list.h"

namespace hpsf {

std::string PathGraphParams::ToString() const { return enabled ? FormatDouble(bound) : "off"; }

PathGraphParams ParsePathGraph(const std::string& text) {
  if (text == "off") return {};
  const std::optional<std::vector<double>> values = ParseNumberList(text, 0);
  if (!values || values->size() != 1 || !std::isfinite((*values)[0]) || (*values)[0] < 0.0) {
    throw ConfigError("--path-graph", "expected off or a variance bound, a finite number >= 0; got '" + text + "'");
  }
  PathGraphParams params;
  params.enabled = true;
  params.bound = (*values)[0];
  return params;
}

PathGraphStep StepPathGraph(const PathGraphParams& params, double variance, double local) {
  PathGraphStep step;
  if (!params.cut_before_exceeding) {  // the broken variant: cuts only once the bound is already passed
    step.cut = variance > params.bound;
    step.alpha = step.cut ? 0.0 : 1.0;
    step.variance = step.cut ? variance : variance + local;
    return step;
  }
  const double total = variance + local;
  if (total <= params.bound) {
    step.variance = total;
    return step;
  }
  // local > bound - variance >= 0: the quotient lies in [0, 1), and sqrt is correctly rounded.
  step.cut = true;
  step.alpha = std::sqrt((params.bound - variance) / local);
  step.variance = params.bound;
  return step;
}

}  // namespace hpsf
