#include "vulkan/spirv_reflection.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <set>
#include <utility>

#include <spirv_cross/spirv_cross_c.h>

#include "core/error.h"

namespace hpsf {
namespace {

std::string ScalarTypeName(spvc_type type) {
  switch (spvc_type_get_basetype(type)) {
    case SPVC_BASETYPE_UINT64:
      return "uint64_t";
    case SPVC_BASETYPE_INT64:
      return "int64_t";
    case SPVC_BASETYPE_FP32:
      return "float";
    case SPVC_BASETYPE_FP64:
      return "double";
    case SPVC_BASETYPE_UINT32:
      return "uint";
    case SPVC_BASETYPE_INT32:
      return "int";
    case SPVC_BASETYPE_STRUCT:
      return "a struct";
    default:
      return "a type of " + std::to_string(spvc_type_get_bit_width(type)) + " bits";
  }
}

// A vector is named with its size, so that a uvec4 binding is not taken for packed-decimal's uint sums.
std::string TypeName(spvc_type type) {
  const unsigned size = spvc_type_get_vector_size(type);
  return size > 1 ? "a vector of " + std::to_string(size) + " " + ScalarTypeName(type) : ScalarTypeName(type);
}

// The element type of every declaration of a storage buffer at `binding` of set 0 (a shader may alias a binding, e.g.
// as 32-bit words); with used_only, of those the entry point uses (statically), not merely declares.
std::set<std::string> ElementTypes(std::span<const std::uint32_t> spirv, const std::string& file, std::uint32_t binding,
                                   bool used_only = false) {
  spvc_context raw_context = nullptr;
  if (spvc_context_create(&raw_context) != SPVC_SUCCESS) throw InputError(file + ": cannot reflect the SPIR-V");
  const std::unique_ptr<spvc_context_s, void (*)(spvc_context)> context(raw_context, spvc_context_destroy);
  spvc_parsed_ir ir = nullptr;
  spvc_compiler compiler = nullptr;
  spvc_resources resources = nullptr;
  const spvc_reflected_resource* buffers = nullptr;
  std::size_t count = 0;
  spvc_set used = nullptr;
  const auto create_resources = [&] {
    if (!used_only) return spvc_compiler_create_shader_resources(compiler, &resources);
    if (spvc_compiler_get_active_interface_variables(compiler, &used) != SPVC_SUCCESS) return SPVC_ERROR_INVALID_SPIRV;
    return spvc_compiler_create_shader_resources_for_active_variables(compiler, &resources, used);
  };
  if (spvc_context_parse_spirv(raw_context, spirv.data(), spirv.size(), &ir) != SPVC_SUCCESS ||
      spvc_context_create_compiler(raw_context, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP, &compiler) !=
          SPVC_SUCCESS ||
      create_resources() != SPVC_SUCCESS ||
      spvc_resources_get_resource_list_for_type(resources, SPVC_RESOURCE_TYPE_STORAGE_BUFFER, &buffers, &count) !=
          SPVC_SUCCESS) {
    throw InputError(file + ": the SPIR-V does not reflect: " + spvc_context_get_last_error_string(raw_context));
  }
  std::set<std::string> types;
  for (std::size_t b = 0; b < count; ++b) {
    if (spvc_compiler_get_decoration(compiler, buffers[b].id, SpvDecorationDescriptorSet) != 0 ||
        spvc_compiler_get_decoration(compiler, buffers[b].id, SpvDecorationBinding) != binding) {
      continue;
    }
    const spvc_type block = spvc_compiler_get_type_handle(compiler, buffers[b].base_type_id);
    if (spvc_type_get_num_member_types(block) == 0) continue;
    types.insert(TypeName(spvc_compiler_get_type_handle(compiler, spvc_type_get_member_type(block, 0))));
  }
  return types;
}

std::string Listed(const std::set<std::string>& types) {
  std::string found;
  for (const std::string& type : types) found += (found.empty() ? "" : " and ") + type;
  return found;
}

}  // namespace

std::vector<std::uint32_t> ReadSpirvFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the SPIR-V file");
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty() || bytes.size() % 4 != 0) {
    throw InputError(path + ": " + std::to_string(bytes.size()) +
                     " bytes is not a whole number of 32-bit SPIR-V words");
  }
  std::vector<std::uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  if (words[0] != 0x07230203u) throw InputError(path + ": byte 0: not SPIR-V (magic number 0x07230203 expected)");
  return words;
}

Accumulation SumsAccumulation(std::span<const std::uint32_t> spirv, const std::string& file,
                              std::uint32_t sums_binding) {
  const std::set<std::string> types = ElementTypes(spirv, file, sums_binding);
  if (types.empty()) {
    throw InputError(file + ": declares no storage buffer at binding " + std::to_string(sums_binding) +
                     " (the sums of the stable buffer interface)");
  }
  if (types == std::set<std::string>{"uint64_t"}) return Accumulation::kFixed64;
  if (types == std::set<std::string>{"float"}) return Accumulation::kFloat32;
  if (types == std::set<std::string>{"uint"}) return Accumulation::kPackedDecimal;
  throw InputError(file + ": binding " + std::to_string(sums_binding) + " (sums) holds " + Listed(types) +
                   "; the stable buffer interface takes uint64_t (fixed64), float (float32) or uint "
                   "(packed-decimal)");
}

TagViews DeclaredTagViews(std::span<const std::uint32_t> spirv, const std::string& file, std::uint32_t tags_binding) {
  // A shader written against table_interface.glsl declares both views; the ones it uses are the widths it handles.
  std::set<std::string> types = ElementTypes(spirv, file, tags_binding, true);
  TagViews views;
  views.fingerprint = types.erase("uint") > 0;
  views.full = types.erase("uint64_t") > 0;
  if (!types.empty()) {
    throw InputError(file + ": binding " + std::to_string(tags_binding) + " (tags) holds " + Listed(types) +
                     "; the stable buffer interface takes uint (fingerprints) or uint64_t (full keys)");
  }
  return views;
}

bool ReadsCountWords(std::span<const std::uint32_t> spirv, const std::string& file, std::uint32_t counts_binding) {
  return ElementTypes(spirv, file, counts_binding, true).count("uint") > 0;
}

std::vector<TeamTagReader> TeamTagReaders(const TeamShader& accumulate, const TeamShader& eviction,
                                          const TeamShader& compaction, const TeamShader& transport) {
  std::vector<TeamTagReader> readers;
  for (const auto& [shader, binding] :
       {std::pair{&accumulate, 2u}, std::pair{&eviction, 0u}, std::pair{&compaction, 1u}, std::pair{&transport, 3u}}) {
    if (!shader->spirv.empty())
      readers.push_back({shader->name, binding, DeclaredTagViews(shader->spirv, shader->name, binding)});
  }
  return readers;
}

}  // namespace hpsf
