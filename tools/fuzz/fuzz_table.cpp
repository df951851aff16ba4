// fuzz_table: the hash table against its oracle. The input decodes (fuzz_batch.h) into a small table (1 to 256
// slots, any probe limit, 8 to 32 fingerprint bits, fixed64, float32 or packed-decimal) and a batch built to collide,
// which the reference and the emulated backend filter, faithfully (the input's warp size and schedule) and fast.
// A bug: any table checker violation, any breach of the cross-check contract (levels 2 to 4, the same code as
// hpsf crosscheck: verifier/contract/contract_levels.h), a kernel fault, an exception, or a sanitizer report.
// Packed-decimal's 32-bit sums wrap under a batch bright enough: that input is beyond the layout, not a bug. The
// table checker names a slot whose exact sum passed 32 bits at level 2; a verdict that names one is classified as
// beyond the layout and not reported (fuzz_batch.h, BeyondPackedDecimal).
// HPSF_FUZZ_DEFECT=D9 (or D2, D3, D8, D8-unwrapped, D13) runs a known broken kernel instead, to show the target finds
// it.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "emulated/defect_injection.h"
#include "tools/fuzz/fuzz_batch.h"
#include "verifier/contract/contract_levels.h"

namespace hpsf {
namespace {

Defect DefectUnderTest() {
  static const Defect defect = [] {
    const char* name = std::getenv("HPSF_FUZZ_DEFECT");
    return ParseDefect(name != nullptr ? name : "none");
  }();
  return defect;
}

void Report(const FuzzCase& c, const std::string& mode, const CrosscheckReport& report) {
  std::fprintf(stderr, "fuzz_table: the %s emulator breaks the contract:\n", mode.c_str());
  for (const LevelVerdict& v : report.levels) {
    for (const std::string& failure : v.failures)
      std::fprintf(stderr, "  level %d %s: %s\n", v.level, v.name.c_str(), failure.c_str());
  }
  std::fprintf(stderr, "%s", c.ToString().c_str());
}

}  // namespace
}  // namespace hpsf

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hpsf;
  FuzzedDataProvider input(data, size);
  const FuzzCase c = DecodeFuzzCase(input, true);
  for (const EmulatorOptions* emulator : {&c.faithful, &c.fast}) {
    const CrosscheckReport report = CrosscheckEmulated(c.batch, c.config, *emulator, DefectUnderTest());
    if (BeyondPackedDecimal(c.config, report)) continue;
    if (!report.Passed()) {
      Report(c, emulator->mode == simt::Mode::kFast ? "fast" : "faithful", report);
      std::abort();
    }
  }
  return 0;
}
