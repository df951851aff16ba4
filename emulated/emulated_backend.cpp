#include "emulated/emulated_backend.h"

#include <utility>

namespace hpsf {

const Image& EmulatedBackend::FilterFrameInto(const RecordBatch& batch, const FilterConfig& config,
                                              std::uint32_t index) {
  const FrameEffects effects = PlanFrameEffects(config, index);
  const HashTableDump* previous = index == 0 ? nullptr : &run_->table;
  EmulatedRun next =
      EmulatedFilter(batch, config, options_, kernel_, previous, eviction_kernels_, &effects, &workspace_);
  // The previous frame's run has served as `previous`: its arrays serve the next frame.
  if (run_) workspace_.Recycle(std::move(*run_));
  run_ = std::move(next);
  return run_->image;
}

void EmulatedBackend::ForgetTable() {
  if (run_) workspace_.Recycle(std::move(*run_));
  run_.reset();
}

}  // namespace hpsf
