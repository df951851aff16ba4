#include "tools/hpsf/frame_soundness.h"

#include <cmath>
#include <string>

#include "core/fixed_point_scale.h"

namespace hpsf {

void RequireSoundFrame(const Backend& backend, const Image& image, const FilterConfig& config) {
  const FilterResult* exact = backend.LastExactResult();
  const HashedRun* hashed = backend.LastHashedRun();
  const std::uint64_t wraps = exact ? exact->stats.fixed_point_wraps : hashed ? hashed->wraps : 0;
  const int bits = exact ? exact->stats.fixed_point_bits : hashed ? hashed->table.fixed_point_bits : 0;
  const std::string frame = "frame " + std::to_string(config.frame) + ": ";
  if (wraps > 0 && config.accumulation != Accumulation::kPackedDecimal) {
    throw FixedPointRangeError(
        config.fixed_point_bits ? "--fixed-point-bits" : "--accum",
        frame + std::to_string(wraps) + " fixed64 sums wrapped: the table's light outgrew what F = " +
            std::to_string(bits) + " fraction bits hold (chosen " +
            (config.fixed_point_bits ? "by --fixed-point-bits" : "for the first frame and --frames") +
            "; several filtered bounces can grow it frame after frame without bound). Nothing written: " +
            (config.fixed_point_bits ? "give fewer fraction bits" : "give more --frames, which leaves F more room") +
            ", or filter in float32");
  }
  std::uint64_t not_finite = 0;
  for (const glm::vec3& p : image.pixels)
    not_finite += !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  if (not_finite > 0) {
    throw ConfigError("--accum", frame + std::to_string(not_finite) +
                                     " pixels are not finite: the table's sums outgrew " +
                                     ToString(config.accumulation) + ". Nothing written");
  }
}

}  // namespace hpsf
