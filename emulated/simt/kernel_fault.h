// A kernel did what a GPU would not survive or would silently corrupt: today, a global-memory access outside
// its buffer (docs/design/defects.md, D8, a probe that runs off the end). The emulator stops the launch and names the
// thread, the buffer and the index, where a GPU would write into a neighbouring allocation.
#ifndef HPSF_EMULATED_SIMT_KERNEL_FAULT_H
#define HPSF_EMULATED_SIMT_KERNEL_FAULT_H

#include <stdexcept>
#include <string>

namespace hpsf::simt {

class KernelFault : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace hpsf::simt

#endif  // HPSF_EMULATED_SIMT_KERNEL_FAULT_H
