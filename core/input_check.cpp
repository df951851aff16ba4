#include "core/input_check.h"

#include "core/shared/float_bits.h"

namespace hpsf {
namespace {

bool AnyNonFinite(glm::vec4 v) {
  return shared::IsNonFinite(v.x) || shared::IsNonFinite(v.y) || shared::IsNonFinite(v.z) || shared::IsNonFinite(v.w);
}
bool AnyNegative(glm::vec4 v) {
  return shared::IsNegative(v.x) || shared::IsNegative(v.y) || shared::IsNegative(v.z) || shared::IsNegative(v.w);
}

}  // namespace

InputVerdict CheckRecordInputs(const Record& r) {
  if (AnyNonFinite(r.radiance_before)) return InputVerdict::kNonFinite;
  if (AnyNegative(r.radiance_before)) return InputVerdict::kNegative;
  if (!shared::RecordHasVertex(r)) return InputVerdict::kAccepted;
  for (const glm::vec4& v : {r.position, r.normal, r.tangent, r.bitangent, r.previous, r.contribution, r.throughput}) {
    if (AnyNonFinite(v)) return InputVerdict::kNonFinite;
  }
  // position.w is d_prefix, a length.
  if (shared::IsNegative(r.position.w) || AnyNegative(r.contribution) || AnyNegative(r.throughput)) {
    return InputVerdict::kNegative;
  }
  return InputVerdict::kAccepted;
}

const char* ToString(InputVerdict verdict) {
  switch (verdict) {
    case InputVerdict::kAccepted:
      return "accepted";
    case InputVerdict::kNonFinite:
      return "non-finite";
    case InputVerdict::kNegative:
      return "negative";
  }
  return "?";
}

}  // namespace hpsf
