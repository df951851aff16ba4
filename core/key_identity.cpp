#include "core/key_identity.h"

#include "core/error.h"

namespace hpsf {

KeyIdentity ParseKeyIdentity(const std::string& text) {
  if (text == "fingerprint") return KeyIdentity::kFingerprint;
  if (text == "full") return KeyIdentity::kFull;
  throw ConfigError("--key-identity", "expected fingerprint or full; got '" + text + "'");
}

std::string ToString(KeyIdentity identity) { return identity == KeyIdentity::kFull ? "full" : "fingerprint"; }

}  // namespace hpsf
