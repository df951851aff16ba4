// The HTML report of `hpsf check --html`: one self-contained page (check.tpl, with the diff report's
// style) holding a row per gate case in gate order, its outcome, time and first failure or warning, unfolding to
// every failure, the command that reproduces it, its repro bundle and a link to its own report (a golden case's
// comparisons); above them the run's split by family. A merge of shards renders the same page as the unsharded run.
#ifndef HPSF_TOOLS_HPSF_CHECK_HTML_REPORT_H
#define HPSF_TOOLS_HPSF_CHECK_HTML_REPORT_H

#include <string>

#include "verifier/gate/check_report.h"

namespace hpsf {

// `page` is where the page will be written: links to the cases' own reports are relative to its folder.
std::string RenderCheckHtml(const CheckReport& report, const std::string& page);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_CHECK_HTML_REPORT_H
