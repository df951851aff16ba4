// What a user's accumulate shader declares, read from its SPIR-V with SPIRV-Cross's reflection (Debian's
// libspirv-cross-c-shared): the element type of binding 3 of set 0, the table's sums, decides the mode the shader
// accumulates in (uint64_t: fixed64, float: float32). A shader run in the other mode would read its sums with the
// wrong layout and report nonsense, so a mismatch is refused before anything runs.
#ifndef HPSF_VULKAN_SPIRV_REFLECTION_H
#define HPSF_VULKAN_SPIRV_REFLECTION_H

#include <cstdint>
#include <span>
#include <string>

#include "core/filter_config.h"

namespace hpsf {

// The mode of the sums binding of `spirv` (the contents of `file`, named in messages): binding 3 of an accumulate
// shader, 1 of a resolve shader. InputError when the module does not parse, declares no storage buffer at that
// binding, or declares it with another element type (or with both), naming the types found.
Accumulation SumsAccumulation(std::span<const std::uint32_t> spirv, const std::string& file,
                              std::uint32_t sums_binding = 3);

}  // namespace hpsf

#endif  // HPSF_VULKAN_SPIRV_REFLECTION_H
