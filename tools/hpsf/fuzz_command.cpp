#include "tools/hpsf/fuzz_command.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/backend_registry.h"
#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "tools/hpsf/backend_options.h"
#include "tools/hpsf/filter_options.h"
#include "tools/hpsf/repro_bundle.h"
#include "tools/hpsf/seconds_since.h"
#include "verifier/contract/crosscheck.h"
#include "verifier/fuzzing/adversarial_case.h"
#include "verifier/fuzzing/case_shrinker.h"
#include "vulkan/spirv_reflection.h"

namespace hpsf {
namespace {

using Clock = std::chrono::steady_clock;

struct FuzzOptions {
  std::string backend = "emulated";
  std::string defect = "none";
  std::string accumulation;  // empty: both for the built-in kernels; a user's shader must name its mode
  std::string probing;       // empty: any for the built-in kernels, linear for a user's shader
  VulkanBackendOptions vulkan;
  std::optional<double> seconds;
  std::optional<std::uint64_t> runs;
  std::uint32_t seed = 1;
  std::uint32_t max_records = 96;
  std::string repro_dir = "hpsf-fuzz-repro";
  // What a team's accumulate and resolve shaders implement beyond one level: levels, search.
  std::vector<std::string> shaders_know;
  bool json = false;
};

// The F (fixed64 fraction bits) the runs used: each run's batch chooses its own.
struct FixedPointRange {
  int min = 0, max = 0;
  bool any = false;
  void Add(int bits) {
    min = any ? std::min(min, bits) : bits;
    max = any ? std::max(max, bits) : bits;
    any = true;
  }
  std::string ToString() const {
    if (!any) return "no fixed64 run";
    return "fixed64 at F " + (min == max ? std::to_string(min) : std::to_string(min) + " to " + std::to_string(max));
  }
};

// One case through the checker: one frame, or a sequence through one table per backend.
// A case whose later frame is brighter than the F its first frame chose cannot be filtered (its conversions leave
// fixed64's range: core/fixed_point_scale.h); it judges nothing, and is counted as refused, never as a pass.
std::optional<CrosscheckReport> Check(Crosschecker& checker, const AdversarialCase& c) {
  try {
    return checker.CheckFrames(c.Frames(), c.config, c.emulator);
  } catch (const FixedPointRangeError&) {
    return std::nullopt;
  }
}

bool Fails(const std::optional<CrosscheckReport>& report) { return report && !report->Passed(); }
bool Passes(const std::optional<CrosscheckReport>& report) { return report && report->Passed(); }

struct Failure {
  std::uint64_t run = 0;
  double seconds_to_find = 0;
  AdversarialCase found;
  CrosscheckReport found_report;
  ShrinkResult shrink;
  double shrink_seconds = 0;
  CrosscheckReport report;        // of the shrunk case, or of the case as found when the shrunk one stopped failing
  bool timing_dependent = false;  // the shrunk case passed every rerun: the bundle holds the case as found
};

// How often a case is checked before it counts as passing while shrinking: the emulator replays its schedule, but
// a race on a device fails only on some runs (lavapipe's worker threads interleave workgroups by timing).
int Tries(const BackendInfo& backend) { return backend.on_device ? 3 : 1; }

// The first failing report of up to `tries` checks of c, or the last passing one.
std::optional<CrosscheckReport> CheckUntilFails(Crosschecker& checker, const AdversarialCase& c, int tries) {
  std::optional<CrosscheckReport> report;
  for (int t = 0; t < tries; ++t) {
    report = Check(checker, c);
    if (!Passes(report)) break;
  }
  return report;
}

nlohmann::json ToJson(const FuzzOptions& o, std::uint64_t runs, std::uint64_t refused, double seconds,
                      const std::array<std::uint64_t, kAdversarialFamilies>& families,
                      const FixedPointRange& fixed_point, const std::optional<Failure>& failure) {
  nlohmann::json j = {{"version", 1},
                      {"command", "fuzz"},
                      {"backend", o.backend},
                      {"defect", o.defect},
                      {"accumulate_spv", o.vulkan.accumulate_spv},
                      {"eviction_spv", o.vulkan.eviction_spv},
                      {"temporal_spv", o.vulkan.temporal_spv},
                      {"resolve_spv", o.vulkan.resolve_spv},
                      {"compaction_spv", o.vulkan.compaction_spv},
                      {"transport_spv", o.vulkan.transport_spv},
                      {"key_source", o.vulkan.shader_keys ? "shader" : "core"},
                      {"shaders_know", o.shaders_know},
                      {"accum", o.accumulation.empty() ? "both" : o.accumulation},
                      {"probing", o.probing.empty() ? (o.vulkan.accumulate_spv.empty() ? "any" : "linear") : o.probing},
                      {"seed", o.seed},
                      {"runs", runs},
                      {"refused", refused},
                      {"seconds", seconds},
                      {"runs_per_second", seconds > 0 ? double(runs) / seconds : 0.0},
                      {"passed", !failure.has_value()}};
  j["fixed_point_bits"] =
      fixed_point.any ? nlohmann::json{{"min", fixed_point.min}, {"max", fixed_point.max}} : nlohmann::json(nullptr);
  for (int f = 0; f < kAdversarialFamilies; ++f)
    j["runs_per_family"][ToString(AdversarialFamily(f))] = families[std::size_t(f)];
  if (failure) {
    j["failure"] = {{"run", failure->run},
                    {"seconds_to_find", failure->seconds_to_find},
                    {"family", ToString(failure->found.family)},
                    {"records", failure->found.Records()},
                    {"frames", failure->found.later.size() + 1},
                    {"case", failure->found.ToString()},
                    {"shrunk_records", failure->shrink.shrunk.Records()},
                    {"shrunk_frames", failure->shrink.shrunk.later.size() + 1},
                    {"shrunk_case", failure->shrink.shrunk.ToString()},
                    {"shrink_checks", failure->shrink.checks},
                    {"shrink_seconds", failure->shrink_seconds},
                    {"shrink_exhausted", failure->shrink.exhausted},
                    {"timing_dependent", failure->timing_dependent},
                    {"repro_dir", o.repro_dir},
                    {"report", failure->report.ToJson()}};
  }
  return j;
}

int Run(FuzzOptions& o, bool options_only) {
  const BackendInfo& backend = FindBackend(o.backend, "--backend");
  if (!backend.hashed) {
    throw ConfigError("--backend", "the reference is the oracle; fuzz " + BackendNames(true));
  }
  const Defect defect = ParseDefect(o.defect);
  if (defect != Defect::kNone && backend.kind != BackendKind::kEmulated) {
    throw ConfigError("--inject-defect",
                      "breaks the emulated backend's kernel; for Vulkan give a broken shader with --accumulate-spv");
  }
  const std::pair<const char*, const std::string*> shaders[] = {
      {"--accumulate-spv", &o.vulkan.accumulate_spv}, {"--eviction-spv", &o.vulkan.eviction_spv},
      {"--temporal-spv", &o.vulkan.temporal_spv},     {"--resolve-spv", &o.vulkan.resolve_spv},
      {"--compaction-spv", &o.vulkan.compaction_spv}, {"--transport-spv", &o.vulkan.transport_spv}};
  for (const auto& [option, path] : shaders) {
    if (!path->empty() && !backend.runs_user_shaders) {
      throw ConfigError(option, "runs on the Vulkan backend; add --backend vulkan");
    }
  }
  if ((o.accumulation.empty() || o.accumulation == "both") && !o.vulkan.resolve_spv.empty()) {
    throw ConfigError(
        "--accum", "say which mode the shader given with --resolve-spv resolves: fixed64, float32 or packed-decimal");
  }
  if (o.accumulation.empty() && !o.vulkan.accumulate_spv.empty()) {
    throw ConfigError("--accum",
                      "say which mode the shader given with --accumulate-spv accumulates in: fixed64, float32, "
                      "packed-decimal or both");
  }
  std::optional<Accumulation> accumulation;
  if (!o.accumulation.empty() && o.accumulation != "both") accumulation = ParseAccumulation(o.accumulation);
  std::optional<ProbeKind> probing;
  if (o.probing.empty() && !o.vulkan.accumulate_spv.empty()) probing = ProbeKind::kLinear;
  if (!o.probing.empty() && o.probing != "any") {
    const Probing parsed = ParseProbing(o.probing);
    if (parsed.size) throw ConfigError("--probing", "names a scheme only; each case draws its size");
    probing = parsed.kind;
  }
  bool shaders_know_levels = false, shaders_know_search = false;
  for (const std::string& feature : o.shaders_know) {
    if (feature != "levels" && feature != "search") {
      throw ConfigError("--shaders-know", "expected levels or search; got '" + feature + "'");
    }
    shaders_know_levels |= feature == "levels";
    shaders_know_search |= feature == "search";
  }
  if (o.max_records < 2 || o.max_records > 4096) throw ConfigError("--max-records", "must lie in [2, 4096]");
  if (o.seconds && !(*o.seconds > 0)) throw ConfigError("--time", "must be a positive number of seconds");
  if (!o.seconds && !o.runs) o.seconds = 60.0;
  if (options_only) return kExitOk;

  const std::vector<std::string> backends = {"reference", o.backend};
  Crosschecker checker(backends, defect, o.vulkan);  // a bad shader file is bad input here, before any run
  // A broken kernel's races must replay from the schedule, which the emulator's fast mode does not promise.
  // Full keys only where every team shader that reads tags declares a 64-bit view of them (spirv_reflection.h).
  const auto words = [](const std::string& path) {
    return path.empty() ? std::vector<std::uint32_t>{} : ReadSpirvFile(path);
  };
  const std::vector<std::uint32_t> accumulate = words(o.vulkan.accumulate_spv), eviction = words(o.vulkan.eviction_spv),
                                   compaction = words(o.vulkan.compaction_spv), temporal = words(o.vulkan.temporal_spv),
                                   transport = words(o.vulkan.transport_spv);
  bool full_keys = true, fingerprints = true;
  for (const TeamTagReader& team :
       TeamTagReaders({accumulate, o.vulkan.accumulate_spv}, {eviction, o.vulkan.eviction_spv},
                      {compaction, o.vulkan.compaction_spv}, {transport, o.vulkan.transport_spv})) {
    full_keys &= team.views.Takes(KeyIdentity::kFull);
    fingerprints &= team.views.Takes(KeyIdentity::kFingerprint);
  }
  if (!full_keys && !fingerprints) {
    throw ConfigError("--key-identity",
                      "the team shaders given read tags of different widths: no case can run them all");
  }
  // Packed-decimal sums only where a team's eviction, temporal and transport shaders read their 32-bit count words.
  const bool packed_sums =
      (eviction.empty() || ReadsCountWords(eviction, o.vulkan.eviction_spv, kEvictionCountsBinding)) &&
      (temporal.empty() || ReadsCountWords(temporal, o.vulkan.temporal_spv, kTemporalCountsBinding)) &&
      (transport.empty() || ReadsCountWords(transport, o.vulkan.transport_spv, kTransportCountsBinding));
  // Several levels only where hpsf's own kernels add and resolve them (the level-unjittered kernel adds them, wrongly;
  // the level-wrong-count resolve reads them, wrongly).
  // Or where the team says its shaders know them (--shaders-know).
  const bool levels =
      (defect == Defect::kNone || defect == Defect::kLevelUnjittered || defect == Defect::kLevelWrongCount) &&
      ((o.vulkan.accumulate_spv.empty() && o.vulkan.resolve_spv.empty()) || shaders_know_levels);
  // The search where hpsf's own resolve runs it, rightly or as a broken search kernel.
  const bool search_defect = defect == Defect::kSearchClaims || defect == Defect::kSearchStopsAtTombstone ||
                             defect == Defect::kStencilTruncated;
  const bool search = (defect == Defect::kNone || search_defect) &&
                      ((o.vulkan.accumulate_spv.empty() && o.vulkan.resolve_spv.empty()) || shaders_know_search);
  // Level seeding where hpsf's own kernels run, and no team's shader.
  const bool level_change = defect == Defect::kNone && accumulate.empty() && eviction.empty() && compaction.empty() &&
                            temporal.empty() && o.vulkan.resolve_spv.empty();
  // The transport where the emulator runs it, or where Vulkan's accumulate and resolve are hpsf's own (a team's
  // transport shader is judged with them).
  const bool transports =
      !backend.on_device || level_change ||
      (!transport.empty() && defect == Defect::kNone && accumulate.empty() && o.vulkan.resolve_spv.empty());
  // Second moments where hpsf's own accumulate, temporal and eviction passes keep the squares.
  const bool second_moments = defect == Defect::kNone && accumulate.empty() && eviction.empty() && temporal.empty();
  const AdversarialOptions generate{
      o.max_records,  defect == Defect::kNone || search_defect || defect == Defect::kLevelWrongCount,
      accumulation,   backend.on_device,
      probing,        full_keys,
      fingerprints,   packed_sums,
      levels,         search,
      level_change,   transports,
      second_moments, o.vulkan.resolve_spv.empty()};  // interpolation: hpsf's own resolve
  const bool terminal = isatty(STDERR_FILENO) && !o.json;

  const Clock::time_point start = Clock::now();
  Clock::time_point last_progress = start;
  std::array<std::uint64_t, kAdversarialFamilies> families{};
  std::optional<Failure> failure;
  FixedPointRange fixed_point;
  std::uint64_t run = 0, refused = 0;
  for (; !(o.runs && run >= *o.runs) && !(o.seconds && SecondsSince(start) >= *o.seconds); ++run) {
    const AdversarialCase c = MakeAdversarialCase(o.seed, run, generate);
    ++families[std::size_t(c.family)];
    const std::optional<CrosscheckReport> report = Check(checker, c);
    if (!report) {
      ++refused;
      continue;
    }
    if (c.config.accumulation == Accumulation::kFixed64) fixed_point.Add(report->fixed_point_bits);
    if (!report->Passed()) {
      failure = Failure{run, SecondsSince(start), c, *report, {}, 0, {}, false};
      ++run;
      break;
    }
    if (terminal && SecondsSince(last_progress) >= 0.25) {
      last_progress = Clock::now();
      const double elapsed = SecondsSince(start);
      std::fprintf(stderr, "\rfuzz: %llu runs, %.1f runs/s, %.0f s", (unsigned long long)(run + 1),
                   double(run + 1) / elapsed, elapsed);
    }
  }
  if (terminal) std::fprintf(stderr, "\r%60s\r", "");
  const double seconds = SecondsSince(start);

  if (failure) {
    const Clock::time_point shrink_start = Clock::now();
    const int tries = Tries(backend);
    // A failure that does not repeat on every run of the case as found depends on timing: shrinking it would chase
    // luck, so it is bundled as found.
    for (int t = 1; t < tries && !failure->timing_dependent; ++t) {
      failure->timing_dependent = Passes(Check(checker, failure->found));
    }
    if (!failure->timing_dependent) {
      // With a broken kernel or a team's shader, a shrunk case must also pass on hpsf's own kernels and shaders:
      // shrinking may otherwise wander into a failure they share (a sequence whose first frame, its records cut,
      // chooses an F its later frame wraps), which says nothing of the shader. Unless the found case fails there too.
      VulkanBackendOptions own = o.vulkan;
      own.accumulate_spv = own.eviction_spv = own.temporal_spv = own.resolve_spv = own.compaction_spv =
          own.transport_spv = "";
      const bool teams_shader = !o.vulkan.accumulate_spv.empty() || !o.vulkan.eviction_spv.empty() ||
                                !o.vulkan.temporal_spv.empty() || !o.vulkan.resolve_spv.empty() ||
                                !o.vulkan.compaction_spv.empty() || !o.vulkan.transport_spv.empty();
      std::optional<Crosschecker> hpsfs_own;
      if (defect != Defect::kNone || teams_shader) {
        hpsfs_own.emplace(backends, Defect::kNone, own);
        if (!Passes(Check(*hpsfs_own, failure->found))) hpsfs_own.reset();
      }
      failure->shrink =
          ShrinkCase(failure->found,
                     [&](const AdversarialCase& c) {
                       return Fails(CheckUntilFails(checker, c, tries)) && (!hpsfs_own || Passes(Check(*hpsfs_own, c)));
                     },
                     {.accumulation = accumulation.has_value(),
                      .key_identity = !fingerprints,
                      .probing = generate.probing.has_value(),
                      .eviction = !o.vulkan.eviction_spv.empty(),
                      .temporal = !o.vulkan.temporal_spv.empty(),
                      .compaction = !o.vulkan.compaction_spv.empty(),
                      .transport = !o.vulkan.transport_spv.empty()});
      const std::optional<CrosscheckReport> shrunk = CheckUntilFails(checker, failure->shrink.shrunk, 3 * tries);
      failure->timing_dependent = !Fails(shrunk);  // the shrunk case lost the timing it needs
      if (shrunk) failure->report = *shrunk;
    }
    failure->shrink_seconds = SecondsSince(shrink_start);
    if (failure->timing_dependent) {
      failure->shrink.shrunk = failure->found;
      failure->report = failure->found_report;
    }
    const AdversarialCase& shrunk = failure->shrink.shrunk;
    WriteReproBundle(o.repro_dir, shrunk.Frames(), failure->report,
                     CrosscheckArguments(backends, shrunk.config, shrunk.emulator, defect, o.vulkan));
  }

  if (o.json) {
    std::cout << ToJson(o, run, refused, seconds, families, fixed_point, failure).dump(2) << "\n";
  } else if (!failure) {
    std::printf(
        "fuzz: %llu runs in %.1f s (%.1f runs/s), seed %u, %s: every table passed the checker and the contract\n",
        (unsigned long long)run, seconds, double(run) / seconds, o.seed, fixed_point.ToString().c_str());
    if (refused != 0) {
      std::printf("  %llu of them refused as input, not judged: a later frame past the F its first frame chose\n",
                  (unsigned long long)refused);
    }
  } else {
    const Failure& f = *failure;
    std::printf("fuzz: FAIL at run %llu after %.2f s (seed %u; `--seed %u --runs %llu` %s)\n",
                (unsigned long long)f.run, f.seconds_to_find, o.seed, o.seed, (unsigned long long)(f.run + 1),
                f.timing_dependent ? "draws the case again, which fails on some runs only" : "finds it again");
    std::printf("  found: %s\n", f.found.ToString().c_str());
    if (f.timing_dependent) {
      std::printf(
          "  not shrunk (%llu checks, %.2f s): the failure depends on timing (a rerun of the case, or of the "
          "shrunk case, passed), so the bundle holds the case as found, which may need reruns to fail again\n",
          (unsigned long long)f.shrink.checks, f.shrink_seconds);
    } else {
      std::printf("  shrunk in %llu checks (%.2f s)%s: %s\n", (unsigned long long)f.shrink.checks, f.shrink_seconds,
                  f.shrink.exhausted ? ", stopped at the check limit" : "", f.shrink.shrunk.ToString().c_str());
    }
    std::printf("  %s (%s, F %d)\n", f.report.FirstFailure().c_str(), ToString(f.report.accumulation).c_str(),
                f.report.fixed_point_bits);
    std::printf("  repro bundle in %s: reproduce.sh runs `hpsf crosscheck records.hpsfv` with the same options\n",
                o.repro_dir.c_str());
  }
  return failure ? kExitCheckFailed : kExitOk;
}

}  // namespace

void AddFuzzCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<FuzzOptions>();
  CLI::App* c = app.add_subcommand("fuzz",
                                   "Adversarial batches against a backend or your accumulate shader, judged by the "
                                   "table checker and the cross-check contract; a failure is shrunk to a repro bundle");
  c->add_option("--backend", o->backend, "The backend fuzzed beside the reference: " + BackendNames(true))
      ->capture_default_str();
  c->add_option("--accumulate-spv", o->vulkan.accumulate_spv,
                "Vulkan: your accumulate shader (SPIR-V) through the stable buffer interface");
  c->add_option("--eviction-spv", o->vulkan.eviction_spv,
                "Vulkan: your eviction shader (SPIR-V), run in the cases whose sequence evicts");
  c->add_option("--temporal-spv", o->vulkan.temporal_spv,
                "Vulkan: your temporal blend shader (SPIR-V), run in the cases whose sequence blends");
  c->add_option("--compaction-spv", o->vulkan.compaction_spv,
                "Vulkan: your compaction shader (SPIR-V), run in the cases whose sequence compacts");
  c->add_option("--transport-spv", o->vulkan.transport_spv,
                "Vulkan: your transport shader (SPIR-V), run in the cases whose sequence transports light between "
                "frames");
  c->add_option_function<std::string>(
       "--key-source",
       [o](const std::string& text) {
         if (text != "core" && text != "shader") throw ConfigError("--key-source", "core or shader; got " + text);
         o->vulkan.shader_keys = text == "shader";
       },
       "Vulkan: whose keys your accumulate shader writes: core's or its own (shader), judged as given")
      ->default_str("core");
  c->add_option("--resolve-spv", o->vulkan.resolve_spv,
                "Vulkan: your resolve shader (SPIR-V), run in every case; --accum must name its mode");
  c->add_option("--shaders-know", o->shaders_know,
                "Vulkan: what your accumulate and resolve shaders implement, so that cases draw it as for hpsf's own: "
                "levels (--levels, --min-count) and search (--neighbour-search); comma-separated (hpsf's own kernels "
                "draw both without it)")
      ->delimiter(',');
  c->add_option("--accum", o->accumulation,
                "fixed64, float32, packed-decimal or both (the default: drawn per case, a quarter float32 and a sixth "
                "packed-decimal; a shader given with --accumulate-spv must name its mode)");
  c->add_option("--probing", o->probing,
                "linear, bucket, bucket-window or any: the probing scheme of every case (default any, drawn per case; "
                "linear with --accumulate-spv, whose shader may walk no other)");
  c->add_option(
       "--inject-defect", o->defect,
       "Emulated: run a known broken kernel (D2, D3, D8, D8-unwrapped, D9, D11, D13, "
       "count-store-claim-first, count-store-join-first, last-seen-claimer-only, and the shipped bugs "
       "full-bucket-masked, window-past-the-end and weak-cas-old-value; full-key-low-word with --key-identity full; "
       "level-unjittered and level-wrong-count with --levels 2 or more; search-claims, search-stops-at-tombstone and "
       "stencil-truncated, "
       "resolves with --neighbour-search; algorithm-4, Meijer's Algorithm 4 as written)")
      ->capture_default_str();
  CLI::Option* time =
      c->add_option("--time", o->seconds, "Stop after this many seconds (default 60 when --runs is not given)");
  c->add_option("--runs", o->runs, "Stop after this many batches: the same seed and runs judge the same batches")
      ->excludes(time);
  c->add_option("--seed", o->seed, "Seed of the batches and schedules")->capture_default_str();
  c->add_option("--max-records", o->max_records, "Records per batch at most, 2..4096")->capture_default_str();
  c->add_option("--repro-dir", o->repro_dir, "Where a failure's shrunk repro bundle is written")->capture_default_str();
  c->add_option("--vk-device", o->vulkan.device_filter, "Vulkan: the device whose name contains this text");
  c->add_option_function<std::string>(
       "--vk-staging", [o](const std::string& text) { o->vulkan.staging = ParseStagingPolicy(text); },
       "Vulkan: always, never or auto")
      ->default_str("auto");
  c->add_flag("--json", o->json, "Print the versioned report as JSON");
  c->callback([o, &context] { context.exit_code = Run(*o, context.options_only); });
}

}  // namespace hpsf
