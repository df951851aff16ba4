// fuzz_hpsfv: .hpsfv record files through core/record_file.h. Every input is a sequence of frames or an
// hpsf::InputError naming the file and byte; a bug is a crash, a hang, a sanitizer report, any other exception, or
// frames that do not survive a round trip: written back (WriteRecordFile), a file of versions 2 to 4 is byte for byte
// the input (version 1 is read, never written), and read again they are the same frames, deeper records, scattered
// vertices and own lights included.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/record_file.h"
#include "tools/fuzz/scratch_dir.h"

namespace hpsf {
namespace {

constexpr std::size_t kMaxInputBytes = 1 << 20;

bool SameRecords(const std::vector<Record>& a, const std::vector<Record>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Record)) == 0);
}

bool SameBatch(const RecordBatch& a, const RecordBatch& b) {
  return a.frame == b.frame && a.width == b.width && a.height == b.height &&
         a.samples_per_pixel == b.samples_per_pixel &&
         std::memcmp(&a.fov_y_radians, &b.fov_y_radians, sizeof(double)) == 0 && SameRecords(a.records, b.records) &&
         SameRecords(a.deeper, b.deeper) && SameRecords(a.scattered, b.scattered) &&
         a.own_light.size() == b.own_light.size() &&
         (a.own_light.empty() ||
          std::memcmp(a.own_light.data(), b.own_light.data(), a.own_light.size() * sizeof(glm::vec4)) == 0);
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

[[noreturn]] void Fail(const char* problem) {
  std::fprintf(stderr, "fuzz_hpsfv: %s\n", problem);
  std::abort();
}

}  // namespace
}  // namespace hpsf

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hpsf;
  if (size > kMaxInputBytes) return 0;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string input_path = Scratch().Write("input.hpsfv", bytes);
  std::vector<RecordBatch> frames;
  try {
    frames = ReadRecordFrames(input_path);
  } catch (const InputError&) {
    return 0;
  }
  const std::string written = (Scratch().path() / "written.hpsfv").string();
  WriteRecordFile(written, frames);
  std::uint32_t version = 0;
  std::memcpy(&version, data + 8, sizeof version);
  if (version != 1 && ReadBytes(written) != bytes) Fail("the frames written back differ from the file they came from");
  const std::vector<RecordBatch> again = ReadRecordFrames(written);
  if (again.size() != frames.size()) Fail("a different number of frames read again");
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (!SameBatch(again[k], frames[k])) Fail("a frame read again differs from the one written");
  }
  return 0;
}
