#include "tools/hpsf/emulator_options.h"

#include "core/error.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

void AddEmulatorOptions(CLI::App& command, EmulatorFlags& flags) {
  command.add_option("--mode", flags.mode, "Emulator mode: fast (all cores) or faithful (warp steps, scheduled)")
      ->capture_default_str();
  command.add_option("--warp-size", flags.options.warp_size, "Emulated warp size: 8 (lavapipe), 32, 64")
      ->capture_default_str();
  command
      .add_option("--schedule", flags.options.schedule,
                  "Faithful mode: round-robin, random:SEED or pct:SEED:DEPTH (exhaustive: tests only, up to 2 threads)")
      ->capture_default_str();
  command
      .add_option(
          "--spurious-cas", flags.options.spurious_cas,
          "Faithful mode: the share of weak compare-and-swaps that fail spuriously, in [0, 1) (kernels with one "
          "only, such as --inject-defect weak-cas-old-value)")
      ->capture_default_str();
  command.add_option("--vk-device", flags.vulkan.device_filter,
                     "Vulkan backend: the device whose name contains this text");
  command
      .add_option_function<std::string>(
          "--vk-staging", [&flags](const std::string& text) { flags.vulkan.staging = ParseStagingPolicy(text); },
          "Vulkan backend: move data through staging buffers (always), map the kernels' buffers (never), or stage only "
          "where no device memory is host-cached (auto)")
      ->default_str("auto");
  command.add_option("--accumulate-spv", flags.vulkan.accumulate_spv,
                     "Vulkan backend: run this SPIR-V accumulate shader through the stable buffer interface "
                     "(docs/reference/buffer-interface.md)");
  command.add_option("--eviction-spv", flags.vulkan.eviction_spv,
                     "Vulkan backend: run this SPIR-V eviction shader (evict and reclaim passes, "
                     "docs/reference/buffer-interface.md) with --eviction");
  command.add_option("--temporal-spv", flags.vulkan.temporal_spv,
                     "Vulkan backend: run this SPIR-V temporal blend shader (docs/reference/buffer-interface.md) with "
                     "a blending --temporal");
  command.add_option("--compaction-spv", flags.vulkan.compaction_spv,
                     "Vulkan backend: run this SPIR-V compaction shader (the occupied list's gather and prune, "
                     "docs/reference/buffer-interface.md) with --compaction occupied-list");
  command.add_option("--transport-spv", flags.vulkan.transport_spv,
                     "Vulkan backend: run this SPIR-V transport shader (several filtered bounces' lookups in the table "
                     "before the frame, docs/reference/buffer-interface.md) with --transport on");
  command
      .add_option_function<std::string>(
          "--key-source",
          [&flags](const std::string& text) {
            if (text != "core" && text != "shader") throw ConfigError("--key-source", "core or shader; got " + text);
            flags.vulkan.shader_keys = text == "shader";
          },
          "Vulkan backend: whose keys the accumulate shader writes: core's (judged word for word) or the shader's "
          "own (shader: judged as given, against the exact map over its key words)")
      ->default_str("core");
  command.add_option("--resolve-spv", flags.vulkan.resolve_spv,
                     "Vulkan backend: run this SPIR-V resolve shader (docs/reference/buffer-interface.md); its sums "
                     "binding's type must match --accum");
  command
      .add_option(
          "--inject-defect", flags.defect,
          "Self-test of the gate: run a known broken kernel (D2, D3, D8, D8-unwrapped, D9, D11, D13, "
          "count-store-claim-first, count-store-join-first, last-seen-claimer-only, and the shipped bugs "
          "full-bucket-masked, window-past-the-end and weak-cas-old-value; full-key-low-word with --key-identity full; "
          "level-unjittered and level-wrong-count with --levels 2 or more; search-claims, search-stops-at-tombstone "
          "and stencil-truncated, "
          "resolves with --neighbour-search; algorithm-4, Meijer's Algorithm 4 as written)")
      ->capture_default_str();
}

EmulatorOptions ResolveEmulatorOptions(const EmulatorFlags& flags) {
  EmulatorOptions options = flags.options;
  if (flags.mode != "fast" && flags.mode != "faithful")
    throw ConfigError("--mode", "expected fast or faithful; got '" + flags.mode + "'");
  options.mode = flags.mode == "fast" ? simt::Mode::kFast : simt::Mode::kFaithful;
  if (options.mode == simt::Mode::kFaithful && options.schedule == "exhaustive") {
    // Enumerating every interleaving is feasible up to two threads of the accumulate kernel (2772 to 7722
    // schedules; broken_kernel_tests) or three of a two-operation litmus kernel (90); three accumulate threads
    // have over 1e8 (a multinomial of their operations). A render launches one thread per record.
    throw ConfigError(
        "--schedule",
        "exhaustive enumerates every interleaving: feasible up to 2 threads of the accumulate kernel "
        "(thousands of schedules; 3 threads have over 1e8), not for a render; use random:SEED or pct:SEED:DEPTH");
  }
  options.Validate();
  return options;
}

}  // namespace hpsf
