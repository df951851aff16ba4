// Fails the build when a key-path shader could round differently from C++: it reads the SPIR-V binary and
// rejects division, transcendental and fused instructions, float arithmetic without NoContraction, and a
// module that does not declare RTE rounding and signed-zero/Inf/NaN preservation for 32-bit floats.
// Reading the binary (not spirv-dis's text) keeps the check exact; messages name instructions as spirv-dis does.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glslang/SPIRV/GLSL.std.450.h>
#include <glslang/SPIRV/spirv.hpp>

namespace {

struct Instruction {
  spv::Op opcode;
  std::vector<std::uint32_t> operands;
};

std::string DecodeString(const std::vector<std::uint32_t>& words, std::size_t first) {
  std::string s;
  for (std::size_t i = first; i < words.size(); ++i) {
    for (int byte = 0; byte < 4; ++byte) {
      char c = static_cast<char>((words[i] >> (8 * byte)) & 0xFFu);
      if (c == '\0') return s;
      s += c;
    }
  }
  return s;
}

bool ReadModule(const char* path, std::vector<Instruction>& module, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) return error = "cannot read", false;
  if (bytes.size() % 4 != 0 || bytes.size() < 20) return error = "not a SPIR-V module (size)", false;
  std::vector<std::uint32_t> words(bytes.size() / 4);
  std::copy(bytes.begin(), bytes.end(), reinterpret_cast<char*>(words.data()));
  if (words[0] != spv::MagicNumber) return error = "not a SPIR-V module (magic number)", false;
  for (std::size_t at = 5; at < words.size();) {
    std::uint32_t count = words[at] >> 16;
    if (count == 0 || at + count > words.size())
      return error = "truncated instruction at word " + std::to_string(at), false;
    module.push_back({static_cast<spv::Op>(words[at] & 0xFFFFu), {words.begin() + at + 1, words.begin() + at + count}});
    at += count;
  }
  return true;
}

const std::map<std::uint32_t, const char*> kForbiddenGlslStd450 = {
    {GLSLstd450Sin, "Sin"},
    {GLSLstd450Cos, "Cos"},
    {GLSLstd450Tan, "Tan"},
    {GLSLstd450Asin, "Asin"},
    {GLSLstd450Acos, "Acos"},
    {GLSLstd450Atan, "Atan"},
    {GLSLstd450Atan2, "Atan2"},
    {GLSLstd450Pow, "Pow"},
    {GLSLstd450Exp, "Exp"},
    {GLSLstd450Log, "Log"},
    {GLSLstd450Exp2, "Exp2"},
    {GLSLstd450Log2, "Log2"},
    {GLSLstd450Sqrt, "Sqrt"},
    {GLSLstd450InverseSqrt, "InverseSqrt"},
    {GLSLstd450Fma, "Fma"},
    {GLSLstd450Length, "Length"},
    {GLSLstd450Distance, "Distance"},
    {GLSLstd450Cross, "Cross"},
    {GLSLstd450Normalize, "Normalize"},
    {GLSLstd450Reflect, "Reflect"},
    {GLSLstd450Refract, "Refract"},
};

const std::map<spv::Op, const char*> kForbiddenOps = {
    {spv::OpFDiv, "OpFDiv"},
    {spv::OpFRem, "OpFRem"},
    {spv::OpFMod, "OpFMod"},
    {spv::OpDot, "OpDot"},
    {spv::OpOuterProduct, "OpOuterProduct"},
    {spv::OpMatrixTimesMatrix, "OpMatrixTimesMatrix"},
    {spv::OpMatrixTimesVector, "OpMatrixTimesVector"},
    {spv::OpVectorTimesMatrix, "OpVectorTimesMatrix"},
};

// Rounded float arithmetic that a compiler may fuse unless the result carries NoContraction.
const std::map<spv::Op, const char*> kContractibleOps = {
    {spv::OpFAdd, "OpFAdd"},
    {spv::OpFSub, "OpFSub"},
    {spv::OpFMul, "OpFMul"},
    {spv::OpVectorTimesScalar, "OpVectorTimesScalar"},
    {spv::OpMatrixTimesScalar, "OpMatrixTimesScalar"},
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: spirv_lint SHADER.spv\n");
    return 3;
  }
  const char* path = argv[1];
  std::vector<Instruction> module;
  std::string error;
  if (!ReadModule(path, module, error)) {
    std::fprintf(stderr, "%s: %s\n", path, error.c_str());
    return 3;
  }

  std::map<std::uint32_t, std::string> names;
  std::set<std::uint32_t> no_contraction, glsl_std450;
  bool rte32 = false, preserve32 = false;
  for (const Instruction& in : module) {
    const auto& o = in.operands;
    if (in.opcode == spv::OpName && !o.empty()) names[o[0]] = DecodeString(o, 1);
    if (in.opcode == spv::OpExtInstImport && o.size() > 1 && DecodeString(o, 1) == "GLSL.std.450")
      glsl_std450.insert(o[0]);
    if (in.opcode == spv::OpDecorate && o.size() > 1 && o[1] == spv::DecorationNoContraction)
      no_contraction.insert(o[0]);
    if (in.opcode == spv::OpExecutionMode && o.size() > 2 && o[2] == 32) {
      rte32 = rte32 || o[1] == spv::ExecutionModeRoundingModeRTE;
      preserve32 = preserve32 || o[1] == spv::ExecutionModeSignedZeroInfNanPreserve;
    }
  }

  int violations = 0;
  auto report = [&](const char* what, std::uint32_t id) {
    std::string name = names.count(id) ? " (" + names[id] + ")" : "";
    std::fprintf(stderr, "%s: %%%u = %s%s\n", path, id, what, name.c_str());
    ++violations;
  };
  for (const Instruction& in : module) {
    const auto& o = in.operands;
    if (auto it = kForbiddenOps.find(in.opcode); it != kForbiddenOps.end() && o.size() > 1) {
      report((std::string(it->second) + ": inexact in Vulkan, not allowed on the key path").c_str(), o[1]);
    }
    if (auto it = kContractibleOps.find(in.opcode);
        it != kContractibleOps.end() && o.size() > 1 && !no_contraction.count(o[1])) {
      report((std::string(it->second) + " without NoContraction: make the expression precise").c_str(), o[1]);
    }
    if (in.opcode == spv::OpExtInst && o.size() > 3 && glsl_std450.count(o[2])) {
      if (auto it = kForbiddenGlslStd450.find(o[3]); it != kForbiddenGlslStd450.end()) {
        report((std::string("OpExtInst ") + it->second + ": inexact in Vulkan, not allowed on the key path").c_str(),
               o[1]);
      }
    }
  }
  if (!rte32) std::fprintf(stderr, "%s: no RoundingModeRTE execution mode for 32-bit floats\n", path), ++violations;
  if (!preserve32)
    std::fprintf(stderr, "%s: no SignedZeroInfNanPreserve execution mode for 32-bit floats\n", path), ++violations;
  if (violations > 0) {
    std::fprintf(stderr, "%s: %d key-path violation(s)\n", path, violations);
    return 1;
  }
  return 0;
}
