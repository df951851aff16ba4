#include "reference/reference_backend.h"

#include "reference/reference_filter.h"

namespace hpsf {

const Image& ReferenceBackend::FilterFrameInto(const RecordBatch& batch, const FilterConfig& config, bool first) {
  result_ = ReferenceFilter(batch, config, first ? nullptr : &*result_);
  return result_->image;
}

}  // namespace hpsf
