#include "emulated/emulated_backend.h"

#include <utility>

namespace hpsf {

const Image& EmulatedBackend::FilterFrameInto(const RecordBatch& batch, const FilterConfig& config, bool first) {
  EmulatedRun next =
      EmulatedFilter(batch, config, options_, kernel_, first ? nullptr : &run_->table, eviction_kernels_);
  run_ = std::move(next);
  return run_->image;
}

}  // namespace hpsf
