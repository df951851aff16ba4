// The reference behind the Backend interface (core/backend.h): its table is the exact map of cells, carried from
// frame to frame.
#ifndef HPSF_REFERENCE_REFERENCE_BACKEND_H
#define HPSF_REFERENCE_REFERENCE_BACKEND_H

#include <optional>
#include <string>

#include "core/backend.h"
#include "core/filter_result.h"

namespace hpsf {

class ReferenceBackend : public Backend {
 public:
  std::string Name() const override { return "reference"; }
  // The last frame's result: its placements and counts, and every cell of the table. Only after a frame.
  const FilterResult& result() const { return *result_; }
  const FilterResult* LastExactResult() const override { return result_ ? &*result_ : nullptr; }

 protected:
  const Image& FilterFrameInto(const RecordBatch& batch, const FilterConfig& config, std::uint32_t index) override;
  void ForgetTable() override { result_.reset(); }

 private:
  std::optional<FilterResult> result_;
};

}  // namespace hpsf

#endif  // HPSF_REFERENCE_REFERENCE_BACKEND_H
