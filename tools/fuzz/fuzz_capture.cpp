// fuzz_capture: captures (core/capture_file.h) read, their declaration applied and judged (hpsf judge's path,
// verifier/contract/capture_judgement.h). Every input is a capture judged to some verdict or an hpsf::InputError that
// names the file; a bug is a crash, a hang, a sanitizer report, any other exception, or an error that does not name
// the file. Each chunk's checksum is restored before reading whenever the input's structure allows (unless the
// input's last byte is odd), so that mutations reach the values behind them and not only the checksum check.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/capture_file.h"
#include "core/error.h"
#include "core/fnv1a.h"
#include "verifier/contract/capture_judgement.h"
#include "verifier/gate/table_declaration.h"

namespace {

void RestoreChecksums(std::string& bytes) {
  std::size_t at = 16;
  while (bytes.size() >= at + 16) {
    std::uint64_t size;
    std::memcpy(&size, bytes.data() + at + 8, 8);
    at += 16;
    if (size > bytes.size() - at || bytes.size() - at - size < 8) return;
    const std::uint64_t checksum = hpsf::Fnv1a(bytes.data() + at, std::size_t(size));
    at += std::size_t(size);
    std::memcpy(bytes.data() + at, &checksum, 8);
    at += 8;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hpsf;
  if (size > (1 << 16)) return 0;
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (size > 0 && (data[size - 1] & 1u) == 0) RestoreChecksums(bytes);
  try {
    const Capture capture = ReadCaptureBytes(bytes, "fuzz.hpsfc");
    FilterConfig config;
    ApplyTableDeclarationText(capture.declaration, "fuzz.hpsfc: its declaration", config);
    const CrosscheckReport report = JudgeCapture(capture, config);
    if (report.levels.size() != 4) std::abort();
  } catch (const InputError& e) {
    if (std::string(e.what()).rfind("fuzz.hpsfc: ", 0) != 0) {
      std::fprintf(stderr, "fuzz_capture: an error that does not name the file: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
