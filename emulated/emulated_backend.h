// The emulated backend behind the Backend interface (core/backend.h): the table dumped after each frame is the
// device table the next frame's launch starts from.
#ifndef HPSF_EMULATED_EMULATED_BACKEND_H
#define HPSF_EMULATED_EMULATED_BACKEND_H

#include <optional>
#include <string>

#include "core/backend.h"
#include "emulated/emulated_filter.h"

namespace hpsf {

class EmulatedBackend : public Backend {
 public:
  explicit EmulatedBackend(const EmulatorOptions& options, AccumulateKernelFn kernel = AccumulateKernel,
                           EvictionKernels eviction_kernels = {})
      : options_(options), kernel_(kernel), eviction_kernels_(eviction_kernels) {}
  std::string Name() const override { return "emulated"; }
  const HashedRun* LastHashedRun() const override { return run_ ? &*run_ : nullptr; }
  // The last frame's run: the table after it, and its records' keys and placements. Only after a frame.
  const EmulatedRun& run() const { return *run_; }
  const EmulatorOptions& options() const { return options_; }
  FrameTimings LastFrameTimings() const override;

 protected:
  const Image& FilterFrameInto(const RecordBatch& batch, const FilterConfig& config, std::uint32_t index) override;
  void ForgetTable() override;

 private:
  EmulatorOptions options_;
  AccumulateKernelFn kernel_;
  EvictionKernels eviction_kernels_;
  std::optional<EmulatedRun> run_;
  // The arrays of the frame before the last, which the next frame reuses: a steady sequence of frames touches no
  // fresh memory.
  EmulatorWorkspace workspace_;
};

}  // namespace hpsf

#endif  // HPSF_EMULATED_EMULATED_BACKEND_H
