#include "reference/reference_backend.h"

#include "reference/reference_filter.h"

namespace hpsf {

const Image& ReferenceBackend::FilterFrameInto(const RecordBatch& batch, const FilterConfig& config,
                                               std::uint32_t index) {
  const FrameEffects effects = PlanFrameEffects(config, index);
  result_ = ReferenceFilter(batch, config, index == 0 ? nullptr : &*result_, &effects);
  return result_->image;
}

}  // namespace hpsf
