#include "tracer/cache_sampling.h"

#include <string>

#include "core/error.h"

namespace hpsf {

void CacheSampling::Validate() const {
  if (store < 1 || store > kMaxCacheStore) {
    throw ConfigError("--cache-store",
                      "must lie in [1, " + std::to_string(kMaxCacheStore) + "]; got " + std::to_string(store));
  }
  if (length < 1 || length > kMaxCacheLength) {
    throw ConfigError("--cache-length",
                      "must lie in [1, " + std::to_string(kMaxCacheLength) + "]; got " + std::to_string(length));
  }
}

}  // namespace hpsf
