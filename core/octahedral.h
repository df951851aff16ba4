// Octahedral coordinates of a unit normal, quantized to 16 bits per axis on the host (the mapping divides by
// |x| + |y| + |z|, which the key path may not). The shared code keeps the top bits as the normal bucket.
#ifndef HPSF_CORE_OCTAHEDRAL_H
#define HPSF_CORE_OCTAHEDRAL_H

#include <cstdint>

#include <glm/vec3.hpp>

namespace hpsf {

// u in the low 16 bits, v in the high 16 bits; the lower hemisphere is chosen by the sign bit of z.
std::uint32_t PackOctahedral16(glm::vec3 normal);

}  // namespace hpsf

#endif  // HPSF_CORE_OCTAHEDRAL_H
