// One global-memory operation of an emulated GPU thread: what it does, where, with which operands, and what it
// returned. Kernels issue them; the launcher applies them, in an order the schedule decides.
#ifndef HPSF_EMULATED_SIMT_MEMORY_OP_H
#define HPSF_EMULATED_SIMT_MEMORY_OP_H

#include <cstdint>
#include <string>

namespace hpsf::simt {

enum class OpKind : std::uint8_t {
  kLoad,            // plain read
  kStore,           // plain write
  kAtomicAdd,       // integer add, returns the old value
  kAtomicAddFloat,  // 32-bit float add on the bits, returns the old bits
  kAtomicCas,       // compare-and-swap: writes `value` if the word equals `compare`; returns the old value
  kAtomicMin,       // unsigned minimum, returns the old value
  kAtomicOr,        // bitwise or, returns the old value
  kAtomicExchange,  // writes `value`, returns the old value
  // Weak compare-and-swap (WGSL's atomicCompareExchangeWeak, C++'s compare_exchange_weak): as kAtomicCas, but it
  // may fail spuriously, writing nothing where the word equals `compare`; `spurious` says it did. Faithful mode fails
  // it as the launch's WeakCasPolicy decides; fast mode runs the CPU's, which on x86 never fails spuriously.
  kAtomicCasWeak,
};

const char* ToString(OpKind kind);
inline bool IsWrite(OpKind kind) { return kind != OpKind::kLoad; }

struct Address {
  std::uint32_t buffer = 0;
  std::uint64_t index = 0;
  friend bool operator==(const Address&, const Address&) = default;
};

struct MemoryOp {
  OpKind kind = OpKind::kLoad;
  Address address;
  std::uint64_t value = 0;    // store / add operand / CAS desired value
  std::uint64_t compare = 0;  // CAS expected value
  std::uint64_t result = 0;   // the value the operation read (old value for read-modify-writes)
  bool spurious = false;      // kAtomicCasWeak: failed spuriously (set by the launcher before it is applied)
  std::string ToString() const;
};

}  // namespace hpsf::simt

#endif  // HPSF_EMULATED_SIMT_MEMORY_OP_H
