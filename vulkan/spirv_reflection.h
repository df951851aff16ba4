// What a team's shader declares, read from its SPIR-V with SPIRV-Cross's reflection (Debian's
// libspirv-cross-c-shared): the element type of binding 3 of set 0, the table's sums, decides the mode the shader
// accumulates in (uint64_t: fixed64, float: float32), and the element types of its tags binding the key identities
// it reads. A shader run in another mode, or with tags of another width, would read its buffers with the wrong
// layout and report nonsense, so a mismatch is refused before anything runs.
#ifndef HPSF_VULKAN_SPIRV_REFLECTION_H
#define HPSF_VULKAN_SPIRV_REFLECTION_H

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/filter_config.h"

namespace hpsf {

// A SPIR-V binary's words; InputError naming the file when it is missing, empty or not SPIR-V.
std::vector<std::uint32_t> ReadSpirvFile(const std::string& path);

// The mode of the sums binding of `spirv` (the contents of `file`, named in messages): binding 3 of an accumulate
// shader, 1 of a resolve shader. InputError when the module does not parse, declares no storage buffer at that
// binding, or declares it with another element type (or with both), naming the types found.
Accumulation SumsAccumulation(std::span<const std::uint32_t> spirv, const std::string& file,
                              std::uint32_t sums_binding = 3);

// The views a shader uses of a table's tags binding (vulkan/shaders/slot_tags.glsl): uint reads 32-bit
// fingerprints, uint64_t the 64-bit full keys of --key-identity full; hpsf's shaders use both, by a push constant.
// A shader run with tags of a width it does not use would read them with the wrong stride, so VulkanFilter refuses
// it. Declared but unused views (table_interface.glsl declares both) do not count.
// InputError when the module does not parse or declares the binding with another element type.
struct TagViews {
  bool fingerprint = false;  // uint
  bool full = false;         // uint64_t
  bool Declares(KeyIdentity identity) const { return identity == KeyIdentity::kFull ? full : fingerprint; }
  // Whether the shader runs with tags of this identity: it uses that view, or reads no tags at all.
  bool Takes(KeyIdentity identity) const { return !(fingerprint || full) || Declares(identity); }
};
TagViews DeclaredTagViews(std::span<const std::uint32_t> spirv, const std::string& file, std::uint32_t tags_binding);

// Whether a team's pass shader uses a 32-bit view of its counts binding (an eviction shader's 2, a temporal shader's
// 1, a transport shader's 5), the count words of packed-decimal sums (core/shared/packed_sums.h), as eviction.comp and
// temporal.comp do by a push constant. One that reads 64-bit counts only would read count words with the wrong stride,
// so VulkanFilter refuses it with packed-decimal sums.
constexpr std::uint32_t kEvictionCountsBinding = 2;
constexpr std::uint32_t kTemporalCountsBinding = 1;
constexpr std::uint32_t kTransportCountsBinding = 5;
bool ReadsCountWords(std::span<const std::uint32_t> spirv, const std::string& file, std::uint32_t counts_binding);

// A team's shader that reads the table's tags (--accumulate-spv at binding 2, --eviction-spv at 0, --compaction-spv
// at 1, --transport-spv at 3) and the views it uses. The one place those bindings are named, for VulkanFilter's refusal
// and for what hpsf fuzz draws.
struct TeamTagReader {
  std::string name;
  std::uint32_t binding;
  TagViews views;
};
struct TeamShader {
  std::span<const std::uint32_t> spirv;  // empty: the built-in shader, which takes both identities
  std::string name;
};
std::vector<TeamTagReader> TeamTagReaders(const TeamShader& accumulate, const TeamShader& eviction,
                                          const TeamShader& compaction, const TeamShader& transport = {});

}  // namespace hpsf

#endif  // HPSF_VULKAN_SPIRV_REFLECTION_H
