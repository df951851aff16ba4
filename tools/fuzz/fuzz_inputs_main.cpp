// A libFuzzer target as a plain test program, for ctest in a build without libFuzzer: runs the target over every
// file of the corpus folders given as arguments, then over --inputs=N inputs of 1 to 4096 bytes drawn from the
// counter RNG (core/shared/rng.h, seed --seed=S, default 1), so the run is the same on every machine. A crash or
// a sanitizer report fails the test; the last input is kept in fuzz-input.bin (the working folder) for replay.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/shared/rng.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

void RunKept(const std::vector<std::uint8_t>& input) {
  std::ofstream("fuzz-input.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(input.data()), std::streamsize(input.size()));
  LLVMFuzzerTestOneInput(input.data(), input.size());
}

std::uint32_t Bits(std::uint32_t seed, std::uint32_t input, std::uint32_t word) {
  return hpsf::shared::RandomBits({seed, 0u, input, 0u, 0u}, word);
}

}  // namespace

int main(int argc, char** argv) {
  std::uint32_t inputs = 1000, seed = 1;
  std::size_t corpus_files = 0;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("--inputs=", 0) == 0) {
      inputs = std::uint32_t(std::stoul(arg.substr(9)));
    } else if (arg.rfind("--seed=", 0) == 0) {
      seed = std::uint32_t(std::stoul(arg.substr(7)));
    } else {
      for (const auto& entry : std::filesystem::directory_iterator(arg)) {
        std::ifstream in(entry.path(), std::ios::binary);
        RunKept(std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
        ++corpus_files;
      }
    }
  }
  for (std::uint32_t i = 0; i < inputs; ++i) {
    std::vector<std::uint8_t> input(1 + Bits(seed, i, 0) % 4096);
    for (std::size_t b = 0; b < input.size(); b += 4) {
      const std::uint32_t word = Bits(seed, i, std::uint32_t(1 + b / 4));
      std::memcpy(input.data() + b, &word, std::min<std::size_t>(4, input.size() - b));
    }
    RunKept(input);
  }
  std::printf("%zu corpus files and %u generated inputs (seed %u): no crash\n", corpus_files, inputs, seed);
  return 0;
}
