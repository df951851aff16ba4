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

FrameTimings EmulatedBackend::LastFrameTimings() const {
  if (!run_) return {};
  const EmulatedTimings& t = run_->timings;
  return {.transport_ms = t.transport_ms,
          .keys_ms = t.keys_ms + t.fixed_point_ms,
          .accumulate_ms = t.clear_ms + t.accumulate_ms,
          .level_seed_ms = t.level_seed_ms,
          .compaction_ms = t.compaction_ms,
          .settle_ms = t.settle_ms,
          .temporal_ms = t.temporal_ms,
          .eviction_ms = t.eviction_ms,
          .resolve_ms = t.read_back_ms + t.resolve_ms,
          .transfer_ms = std::nullopt};
}

}  // namespace hpsf
