#include "core/key_batch.h"

#include <cstring>
#include <stdexcept>

#include "core/format.h"

namespace hpsf {

void ComputeKeys(std::span<const Record> records, const KeyParams& params, std::span<KeyResult> keys) {
  if (keys.size() != records.size()) throw std::length_error("ComputeKeys: one result per record");
  for (std::size_t i = 0; i < records.size(); ++i) keys[i] = shared::ComputeKey(params, records[i]);
}

std::vector<KeyResult> ComputeKeys(std::span<const Record> records, const KeyParams& params) {
  std::vector<KeyResult> keys(records.size());
  ComputeKeys(records, params, keys);
  return keys;
}

std::array<std::uint32_t, 12> KeyResultWords(const KeyResult& key) {
  std::array<std::uint32_t, 12> words;
  std::memcpy(words.data(), &key, sizeof key);
  return words;
}

const char* KeyResultWordName(int index) {
  static const char* const kNames[12] = {"cell_x", "cell_y",      "cell_z", "level_word", "normal",        "extra",
                                         "slot0",  "fingerprint", "level",  "status",     "identity_high", "padding1"};
  return index >= 0 && index < 12 ? kNames[index] : "?";
}

std::string ToString(const KeyResult& key) {
  std::string s = "[ KeyResult";
  const auto words = KeyResultWords(key);
  for (int i = 0; i < 12; ++i) s += std::string(" ") + KeyResultWordName(i) + ": " + FormatHex(words[i]);
  return s + " ]";
}

}  // namespace hpsf
