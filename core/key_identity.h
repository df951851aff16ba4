// What a slot stores to tell keys apart (`--key-identity fingerprint|full`): a reduced fingerprint, 0 marking an
// empty slot, which two cells may share (an alias the checker classifies); or the full key, 64 bits packed from the
// key words as NVIDIA SHaRC stores its keys (core/shared/full_key.h), which no two cells share, at the price of a
// 64-bit tag and of cells limited to 17 bits per axis (a cell beyond them is unkeyable).
#ifndef HPSF_CORE_KEY_IDENTITY_H
#define HPSF_CORE_KEY_IDENTITY_H

#include <string>

namespace hpsf {

enum class KeyIdentity { kFingerprint, kFull };

// Parses "fingerprint" or "full"; a ConfigError naming --key-identity otherwise.
KeyIdentity ParseKeyIdentity(const std::string& text);
std::string ToString(KeyIdentity identity);

}  // namespace hpsf

#endif  // HPSF_CORE_KEY_IDENTITY_H
