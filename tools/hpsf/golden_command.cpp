#include "tools/hpsf/golden_command.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>

#include "core/error.h"
#include "tools/hpsf/channel_image_file.h"
#include "tools/hpsf/heatmap.h"
#include "tools/hpsf/html_report.h"
#include "tools/hpsf/seconds_since.h"
#include "tools/hpsf/subprocess.h"
#include "verifier/gate/golden_manifest.h"
#include "verifier/metrics/image_comparison.h"
#include "verifier/metrics/statistical_compare.h"

namespace hpsf {
namespace {

namespace fs = std::filesystem;

struct GoldenOptions {
  std::string manifest = "golden/manifest.json";
  std::vector<std::string> cases;
  std::string html;
  bool json = false;
};

// What a check leaves beside the golden when it does not pass: <golden stem>.<backend>.new.exr, .heatmap.png
// and .report.html.
struct Artifacts {
  fs::path new_image, heatmap, report;
  static Artifacts For(const GoldenCase& c, const std::string& backend) {
    const fs::path golden(c.golden);
    const std::string stem = (golden.parent_path() / (golden.stem().string() + "." + backend)).string();
    return {fs::path(stem + ".new.exr"), fs::path(stem + ".heatmap.png"), fs::path(stem + ".report.html")};
  }
  void Remove() const {
    std::error_code ignored;
    fs::remove(new_image, ignored);
    fs::remove(heatmap, ignored);
    fs::remove(report, ignored);
  }
};

struct CheckOutcome {
  std::string case_name, backend;
  DiffVerdict verdict = DiffVerdict::kFail;
  std::string explanation;
  std::optional<ImageComparison> comparison;
  std::optional<StatisticalComparison> statistical;
  std::shared_ptr<const ChannelImage> fresh, golden;  // for the report, when both were read
  std::string render_output;                          // kept when the render itself failed
  std::vector<std::string> artifacts;
  double seconds = 0.0;
};

std::vector<const GoldenCase*> Select(const GoldenManifest& manifest, const std::vector<std::string>& names) {
  std::vector<const GoldenCase*> selected;
  std::set<std::string> wanted(names.begin(), names.end());
  for (const GoldenCase& c : manifest.cases) {
    if (names.empty() || wanted.erase(c.name)) selected.push_back(&c);
  }
  if (!wanted.empty()) throw InputError(manifest.path + ": no case named '" + *wanted.begin() + "'");
  return selected;
}

// A private folder for the renders of one run, in the system's temporary folder (a passing check writes nothing
// beside the goldens), removed when the run ends.
class WorkFolder {
 public:
  WorkFolder() : path_(fs::temp_directory_path() / ("hpsf-golden-" + std::to_string(getpid()))) {
    fs::create_directories(path_);
  }
  ~WorkFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  fs::path File(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

std::string Slug(const std::string& name) {
  std::string slug = name;
  for (char& ch : slug) {
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '.') ch = '_';
  }
  return slug;
}

ReportEntry ReportEntryOf(const CheckOutcome& outcome) {
  ReportEntry entry;
  entry.title = outcome.case_name + " (" + outcome.backend + ")";
  entry.a = outcome.fresh.get();
  entry.b = outcome.golden.get();
  entry.a_label = "new render (" + outcome.backend + ")";
  entry.b_label = "golden " + outcome.golden->path;
  entry.comparison = *outcome.comparison;
  if (outcome.statistical) entry.extra = ToJson(*outcome.statistical);
  return entry;
}

// Renders one case with one backend into `output` (absolute), in the manifest's folder.
ProcessResult Render(const GoldenManifest& manifest, const GoldenCase& c, const std::string& backend,
                     const fs::path& output) {
  std::vector<std::string> argv = {SelfPath()};
  for (const std::string& a : c.Command(backend, fs::absolute(output).string())) argv.push_back(a);
  return RunProcess(argv, manifest.folder);
}

CheckOutcome Check(const GoldenManifest& manifest, const GoldenCase& c, const std::string& backend,
                   const WorkFolder& work) {
  const auto start = std::chrono::steady_clock::now();
  CheckOutcome outcome;
  outcome.case_name = c.name;
  outcome.backend = backend;
  const Artifacts artifacts = Artifacts::For(c, backend);
  artifacts.Remove();  // nothing stale from an earlier run
  const fs::path rendered = work.File(Slug(c.name) + "." + backend + ".exr");
  const ProcessResult render = Render(manifest, c, backend, rendered);
  if (render.exit_code != 0) {
    outcome.explanation = "FAIL: the render exited " + std::to_string(render.exit_code);
    outcome.render_output = render.output;
    outcome.seconds = SecondsSince(start);
    return outcome;
  }
  if (!fs::exists(c.golden)) {
    outcome.explanation = "FAIL: no golden " + c.golden + " (hpsf golden bless '" + c.name + "' writes it)";
  } else {
    outcome.fresh = std::make_shared<const ChannelImage>(ReadChannelImage(rendered.string()));
    outcome.golden = std::make_shared<const ChannelImage>(ReadChannelImage(c.golden));
    ComparisonOptions options;
    options.thresholds = c.thresholds;
    ImageComparison comparison = CompareImages(*outcome.fresh, *outcome.golden, options);
    if (c.comparison == GoldenComparison::kStatistical) {
      const NoisyImage fresh = ToNoisyImage(*outcome.fresh);
      outcome.statistical = CompareStatistically(fresh, ToNoisyImage(*outcome.golden), c.alpha);
      comparison.verdict = outcome.statistical->consistent ? DiffVerdict::kPass : DiffVerdict::kFail;
      comparison.judged_by = outcome.statistical->ToString();
    }
    outcome.verdict = comparison.verdict;
    outcome.explanation = comparison.Explanation();
    outcome.comparison = comparison;
    if (outcome.verdict != DiffVerdict::kPass) {
      WritePng(artifacts.heatmap.string(), RenderHeatmap(*outcome.fresh, *outcome.golden));
      WriteHtmlReport(artifacts.report.string(), RenderHtmlReport("hpsf golden check: " + c.name + " (" + backend + ")",
                                                                  {ReportEntryOf(outcome)}));
    }
  }
  if (outcome.verdict != DiffVerdict::kPass) {
    fs::copy_file(rendered, artifacts.new_image, fs::copy_options::overwrite_existing);
    outcome.artifacts.push_back(artifacts.new_image.string());
    for (const fs::path& left : {artifacts.heatmap, artifacts.report}) {
      if (fs::exists(left)) outcome.artifacts.push_back(left.string());
    }
  }
  outcome.seconds = SecondsSince(start);
  return outcome;
}

void RunCheck(const GoldenOptions& o, int* exit_code) {
  const GoldenManifest manifest = ReadGoldenManifest(o.manifest);
  const std::vector<const GoldenCase*> cases = Select(manifest, o.cases);
  const auto start = std::chrono::steady_clock::now();
  const WorkFolder work;
  std::vector<CheckOutcome> outcomes;
  for (const GoldenCase* c : cases) {
    for (const std::string& backend : c->backends) {
      outcomes.push_back(Check(manifest, *c, backend, work));
      const CheckOutcome& r = outcomes.back();
      if (!o.json) {
        std::printf("%-4s  %-32s %-9s %s (%.2f s)\n", ToString(r.verdict).c_str(), r.case_name.c_str(),
                    r.backend.c_str(), r.explanation.c_str(), r.seconds);
        for (const std::string& a : r.artifacts) std::printf("      left %s\n", a.c_str());
        if (!r.render_output.empty()) std::printf("      the render said:\n%s\n", r.render_output.c_str());
        std::fflush(stdout);
      }
    }
  }
  std::size_t counts[3] = {0, 0, 0};
  DiffVerdict worst = DiffVerdict::kPass;
  for (const CheckOutcome& r : outcomes) {
    ++counts[int(r.verdict)];
    worst = std::max(worst, r.verdict);
  }
  const double seconds = SecondsSince(start);
  if (!o.html.empty()) {
    std::vector<ReportEntry> entries;
    for (const CheckOutcome& r : outcomes) {
      if (r.comparison) entries.push_back(ReportEntryOf(r));
    }
    WriteHtmlReport(o.html, RenderHtmlReport("hpsf golden check " + manifest.path, entries));
  }
  if (o.json) {
    nlohmann::json report = {{"hpsf_report", "golden check"}, {"version", 1}, {"manifest", manifest.path}};
    report["checks"] = nlohmann::json::array();
    for (const CheckOutcome& r : outcomes) {
      nlohmann::json check = {
          {"case", r.case_name},          {"backend", r.backend},     {"verdict", ToString(r.verdict)},
          {"explanation", r.explanation}, {"artifacts", r.artifacts}, {"seconds", r.seconds}};
      if (r.comparison) check["comparison"] = ToJson(*r.comparison);
      if (r.statistical) check["statistical"] = ToJson(*r.statistical);
      if (!r.render_output.empty()) check["render_output"] = r.render_output;
      report["checks"].push_back(check);
    }
    if (!o.html.empty()) report["outputs"]["html"] = o.html;
    report["summary"] = {{"checks", outcomes.size()}, {"pass", counts[0]},          {"warn", counts[1]},
                         {"fail", counts[2]},         {"verdict", ToString(worst)}, {"seconds", seconds}};
    std::cout << report.dump(2) << "\n";
  } else {
    std::printf("golden check %s: %zu checks of %zu cases: %zu pass, %zu warn, %zu fail (%.1f s): %s\n",
                manifest.path.c_str(), outcomes.size(), cases.size(), counts[0], counts[1], counts[2], seconds,
                ToString(worst).c_str());
    if (!o.html.empty()) std::printf("wrote %s\n", o.html.c_str());
  }
  *exit_code = ExitCode(worst);
}

// A golden several cases compare against (fixed64 by every backend, float32 with tolerance) is written by the
// first case in the manifest that names it, whichever of them was asked for.
void RunBless(const GoldenOptions& o) {
  const GoldenManifest manifest = ReadGoldenManifest(o.manifest);
  std::vector<const GoldenCase*> owners;
  std::set<std::string> goldens;
  for (const GoldenCase* c : Select(manifest, o.cases)) goldens.insert(c->golden);
  for (const GoldenCase& c : manifest.cases) {
    if (goldens.erase(c.golden)) owners.push_back(&c);
  }
  const WorkFolder work;
  for (const GoldenCase* c : owners) {
    const std::string& backend = c->backends.front();
    const fs::path rendered = work.File(Slug(c->name) + ".exr");
    const ProcessResult render = Render(manifest, *c, backend, rendered);
    if (render.exit_code != 0) {
      throw InputError(c->name + ": the render exited " + std::to_string(render.exit_code) + ":\n" + render.output);
    }
    std::string what;
    if (!fs::exists(c->golden)) {
      what = "new";
    } else {
      ComparisonOptions exact;
      exact.thresholds = {DiffMetric::kMaxAbs, 0.0, 0.0};
      try {
        const ImageComparison change =
            CompareImages(ReadChannelImage(rendered.string()), ReadChannelImage(c->golden), exact);
        if (change.verdict == DiffVerdict::kPass && change.metadata.empty()) {
          std::printf("unchanged  %-32s %s\n", c->name.c_str(), c->golden.c_str());
          continue;
        }
        what = "changed: " + change.Explanation() + ", rmse " + std::to_string(change.metrics.rmse);
        for (const MetadataDifference& d : change.metadata) what += "; " + d.ToString();
      } catch (const InputError& e) {
        // Another size or other channels (a format that grew a layer), or an old golden that no longer reads:
        // blessing is how it is replaced, so say why it could not be compared and write the new one.
        what = std::string("changed: the old golden cannot be compared: ") + e.what();
      }
    }
    fs::create_directories(fs::path(c->golden).parent_path());
    fs::copy_file(rendered, c->golden, fs::copy_options::overwrite_existing);
    std::printf("blessed    %-32s %s (%s, rendered by %s)\n", c->name.c_str(), c->golden.c_str(), what.c_str(),
                backend.c_str());
  }
}

}  // namespace

void AddGoldenCommand(CLI::App& app, CommandContext& context) {
  CLI::App* golden = app.add_subcommand("golden", "Golden images: check every case, or bless (rewrite) goldens");
  golden->require_subcommand(1);
  auto check = std::make_shared<GoldenOptions>();
  CLI::App* c = golden->add_subcommand(
      "check",
      "Render every case with each backend and compare with its golden: exit 0 pass, 1 warn, 2 fail, 3 bad "
      "manifest. A case that does not pass leaves GOLDEN.BACKEND.new.exr, .heatmap.png and .report.html "
      "beside its golden");
  c->add_option("cases", check->cases, "Only these cases (default: all)");
  c->add_option("--manifest", check->manifest, "The manifest")->capture_default_str();
  c->add_option("--html", check->html, "Write one HTML report of every comparison here");
  c->add_flag("--json", check->json, "Print the report as JSON");
  c->callback([check, &context] {
    if (!context.options_only) RunCheck(*check, &context.exit_code);
  });
  auto bless = std::make_shared<GoldenOptions>();
  CLI::App* b = golden->add_subcommand("bless",
                                       "Render cases with their first backend and rewrite their goldens, "
                                       "saying what changed (the only writer of goldens)");
  b->add_option("cases", bless->cases, "Only these cases (default: all)");
  b->add_option("--manifest", bless->manifest, "The manifest")->capture_default_str();
  b->callback([bless, &context] {
    if (!context.options_only) RunBless(*bless);
  });
}

}  // namespace hpsf
