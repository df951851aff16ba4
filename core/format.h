// Readable, exact text for floats and vectors in ToString() and failure messages: the shortest decimal that
// round-trips, with the bit pattern where it matters.
#ifndef HPSF_CORE_FORMAT_H
#define HPSF_CORE_FORMAT_H

#include <string>

#include <glm/vec3.hpp>

namespace hpsf {

std::string FormatFloat(float x);          // shortest round-trip decimal, e.g. "0.1", "-0", "inf"
std::string FormatDouble(double x);        // the same for a double
std::string FormatFloatBits(float x);      // "0.1 (0x3dcccccd)"
std::string FormatVec3(glm::vec3 v);       // "(0.1, -0, 3)"
std::string FormatHex(unsigned int bits);  // "0x0000002a"

}  // namespace hpsf

#endif  // HPSF_CORE_FORMAT_H
