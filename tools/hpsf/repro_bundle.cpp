#include "tools/hpsf/repro_bundle.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/record_file.h"
#include "tools/hpsf/version.h"

namespace hpsf {
namespace {

// Nine significant digits give back every float exactly.
std::string ExactFloat(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(value));
  return text;
}

// Seventeen give back every double.
std::string ExactDouble(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string Quoted(const std::string& word) {
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

void WriteReproBundle(const std::string& dir_name, std::span<const RecordBatch> frames, const CrosscheckReport& report,
                      const std::vector<std::string>& crosscheck_arguments) {
  const std::filesystem::path dir = dir_name;
  std::filesystem::create_directories(dir);
  WriteRecordFile((dir / "records.hpsfv").string(), frames);
  std::ofstream(dir / "report.json") << report.ToJson().dump(2) << "\n";
  // A user's shaders travel with the bundle, named relative to it.
  std::vector<std::string> arguments;
  for (std::size_t a = 0; a < crosscheck_arguments.size(); ++a) {
    const std::string& word = crosscheck_arguments[a];
    std::string option, path;  // "--option PATH" or "--option=PATH"
    for (const std::string name : {"--accumulate-spv", "--eviction-spv"}) {
      if (word == name && a + 1 < crosscheck_arguments.size()) {
        option = name;
        path = crosscheck_arguments[++a];
      } else if (word.rfind(name + "=", 0) == 0) {
        option = name;
        path = word.substr(name.size() + 1);
      }
    }
    if (option.empty()) {
      arguments.push_back(word);
      continue;
    }
    const std::string copy = "shaders/" + option.substr(2, option.size() - 6) + ".spv";  // accumulate, eviction
    std::filesystem::create_directories(dir / "shaders");
    std::filesystem::copy_file(path, dir / copy, std::filesystem::copy_options::overwrite_existing);
    arguments.insert(arguments.end(), {option, copy});
  }
  std::string options;
  for (const std::string& argument : arguments) options.append(" ").append(Quoted(argument));
  std::ofstream(dir / "reproduce.sh")
      << "#!/bin/sh\n"
      << "# Reproduces the failed cross-check exactly (same records, options, seed and schedule) from any folder on "
         "any\n"
      << "# machine with hpsf: $HPSF if set, else hpsf on PATH. Writes reproduced.json beside report.json.\n"
      << "cd \"$(dirname \"$0\")\" || exit 3\n"
      << "hpsf=${HPSF:-$(command -v hpsf)}\n"
      << "if [ -z \"$hpsf\" ]; then echo \"reproduce.sh: no hpsf: set HPSF=/path/to/hpsf or put hpsf on PATH\" >&2; "
         "exit 3; fi\n"
      << "written=" << Quoted(std::string("hpsf ") + kHpsfVersion) << "\n"
      << "running=$(\"$hpsf\" --version 2>/dev/null)\n"
      << "[ \"$running\" = \"$written\" ] || echo \"reproduce.sh: warning: written by $written, reproduced with "
         "${running:-an hpsf that gives no version} ($hpsf)\" >&2\n"
      << "exec \"$hpsf\" crosscheck records.hpsfv" << options << " --repro-dir reproduced --json > reproduced.json\n";
  std::filesystem::permissions(dir / "reproduce.sh", std::filesystem::perms::owner_exec,
                               std::filesystem::perm_options::add);
}

std::vector<std::string> CrosscheckArguments(const std::vector<std::string>& backends, const FilterConfig& c,
                                             const EmulatorOptions& emulator, Defect defect,
                                             const VulkanBackendOptions& vulkan) {
  std::string backend_list;
  for (const std::string& b : backends) backend_list.append(backend_list.empty() ? "" : ",").append(b);
  std::vector<std::string> a = {"--backends",
                                backend_list,
                                "--filter-width",
                                ExactFloat(c.filter_width_px),
                                "--jitter",
                                ExactFloat(c.jitter_scale),
                                "--normal",
                                c.normal.ToString(),
                                "--lod",
                                c.lod ? "on" : "off",
                                "--cell-size",
                                ExactFloat(c.cell_size),
                                "--level-min=" + std::to_string(c.level_min),
                                "--level-max=" + std::to_string(c.level_max),
                                "--accum",
                                ToString(c.accumulation),
                                "--seed",
                                std::to_string(c.seed),
                                "--capacity",
                                std::to_string(c.capacity),
                                "--probe-limit",
                                std::to_string(c.probe_limit),
                                "--probing",
                                ToString(c.probing),
                                "--fingerprint-bits",
                                std::to_string(c.fingerprint_bits),
                                "--eviction",
                                c.eviction.ToString(),
                                "--temporal",
                                c.temporal.ToString(),
                                "--level-change",
                                c.level_seed.ToString(),
                                "--fixed-point-bits",
                                c.fixed_point_bits ? std::to_string(*c.fixed_point_bits) : "auto"};
  if (c.square_bits) a.insert(a.end(), {"--square-bits", std::to_string(*c.square_bits)});
  if (!c.normal_in_index) a.push_back("--normal-in-fingerprint-only");
  if (c.levels != 1 || c.min_count != 1)
    a.insert(a.end(), {"--levels", std::to_string(c.levels), "--min-count", std::to_string(c.min_count)});
  if (c.neighbour_search) a.insert(a.end(), {"--neighbour-search", "on"});
  if (c.transport) a.insert(a.end(), {"--transport", "on"});
  if (c.second_moments) a.insert(a.end(), {"--second-moments", "on"});
  if (c.interpolation.enabled()) a.insert(a.end(), {"--interpolation", c.interpolation.ToString()});
  if (c.compaction != Compaction::kNone) a.insert(a.end(), {"--compaction", ToString(c.compaction)});
  if (c.key_identity != KeyIdentity::kFingerprint) a.insert(a.end(), {"--key-identity", ToString(c.key_identity)});
  const bool faithful = emulator.mode == simt::Mode::kFaithful;
  a.insert(a.end(), {"--mode", faithful ? "faithful" : "fast"});
  if (faithful) a.insert(a.end(), {"--warp-size", std::to_string(emulator.warp_size), "--schedule", emulator.schedule});
  if (emulator.spurious_cas > 0.0) a.insert(a.end(), {"--spurious-cas", ExactDouble(emulator.spurious_cas)});
  if (defect != Defect::kNone) a.insert(a.end(), {"--inject-defect", ToString(defect)});
  if (!vulkan.device_filter.empty()) a.insert(a.end(), {"--vk-device", vulkan.device_filter});
  if (vulkan.staging != StagingPolicy::kAuto) a.insert(a.end(), {"--vk-staging", ToString(vulkan.staging)});
  if (!vulkan.accumulate_spv.empty()) {
    a.insert(a.end(), {"--accumulate-spv", std::filesystem::absolute(vulkan.accumulate_spv).string()});
  }
  if (!vulkan.eviction_spv.empty()) {
    a.insert(a.end(), {"--eviction-spv", std::filesystem::absolute(vulkan.eviction_spv).string()});
  }
  if (!vulkan.temporal_spv.empty()) {
    a.insert(a.end(), {"--temporal-spv", std::filesystem::absolute(vulkan.temporal_spv).string()});
  }
  if (!vulkan.compaction_spv.empty()) {
    a.insert(a.end(), {"--compaction-spv", std::filesystem::absolute(vulkan.compaction_spv).string()});
  }
  if (!vulkan.transport_spv.empty()) {
    a.insert(a.end(), {"--transport-spv", std::filesystem::absolute(vulkan.transport_spv).string()});
  }
  if (vulkan.shader_keys) a.insert(a.end(), {"--key-source", "shader"});
  if (!vulkan.resolve_spv.empty()) {
    a.insert(a.end(), {"--resolve-spv", std::filesystem::absolute(vulkan.resolve_spv).string()});
  }
  return a;
}

}  // namespace hpsf
