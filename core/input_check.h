// Host-side rejection of inputs a shader must never see: non-finite values anywhere, negative radiance or path
// length. Bit tests only, so the verdict cannot depend on compiler flags. Rejected records never enter a table.
#ifndef HPSF_CORE_INPUT_CHECK_H
#define HPSF_CORE_INPUT_CHECK_H

#include "core/record.h"

namespace hpsf {

enum class InputVerdict { kAccepted, kNonFinite, kNegative };

InputVerdict CheckRecordInputs(const Record& record);
const char* ToString(InputVerdict verdict);

}  // namespace hpsf

#endif  // HPSF_CORE_INPUT_CHECK_H
