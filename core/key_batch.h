// The key path over a whole batch on the CPU (one thread, in record order), and readable key results.
#ifndef HPSF_CORE_KEY_BATCH_H
#define HPSF_CORE_KEY_BATCH_H

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "core/record.h"
#include "core/shared/key.h"

namespace hpsf {

using KeyResult = shared::KeyResult;
using KeyParams = shared::KeyParams;
static_assert(sizeof(KeyResult) == 48 && std::is_standard_layout_v<KeyResult>, "KeyResult must match std430");
static_assert(sizeof(KeyParams) == 64 && std::is_standard_layout_v<KeyParams>, "KeyParams must match std430");

std::vector<KeyResult> ComputeKeys(std::span<const Record> records, const KeyParams& params);
// Into a buffer the caller keeps, of records.size() results.
void ComputeKeys(std::span<const Record> records, const KeyParams& params, std::span<KeyResult> keys);

// The twelve 32-bit words of a result, in layout order: six key words, slot0, fingerprint, level, status and
// two words of padding.
std::array<std::uint32_t, 12> KeyResultWords(const KeyResult& key);
const char* KeyResultWordName(int index);
std::string ToString(const KeyResult& key);

}  // namespace hpsf

#endif  // HPSF_CORE_KEY_BATCH_H
