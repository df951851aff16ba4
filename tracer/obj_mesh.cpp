#include "tracer/obj_mesh.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"

namespace hpsf {
namespace {

// The file's lines as tinyobjloader splits them: at "\n", "\r\n" or a lone "\r".
std::vector<std::string> ObjLines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the mesh file");
  std::vector<std::string> lines(1);
  for (char c; in.get(c);) {
    if (c == '\r' && in.peek() == '\n') continue;
    if (c == '\n' || c == '\r') {
      lines.emplace_back();
    } else {
      lines.back() += c;
    }
  }
  return lines;
}

// Every "v" line must hold three finite numbers; tinyobjloader silently turns unparsable ones into 0. hpsf ignores
// skin weights ("vw") and tinyobjloader never sees them (TextWithoutSkinWeights), but a joint id beyond the range
// of an int is still bad input, named.
void CheckLines(const std::string& path, const std::vector<std::string>& lines) {
  for (std::size_t index = 0; index < lines.size(); ++index) {
    const std::string place = path + ":" + std::to_string(index + 1);
    std::istringstream tokens(lines[index]);
    std::string tag;
    if (!(tokens >> tag)) continue;
    if (tag == "vw") {
      for (std::string token; tokens >> token;) {
        // tinyobjloader reads the value as a float first: 2147483647 rounds to 2^31, past int.
        const float value = float(std::strtod(token.c_str(), nullptr));
        if (!(std::abs(value) < 2147483648.0f)) {
          throw InputError(place + ": skin weight value '" + token + "' lies beyond the range of a joint id");
        }
      }
    }
    if (tag != "v") continue;
    for (int axis = 0; axis < 3; ++axis) {
      std::string token;
      tokens >> token;
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (token.empty() || *end != '\0' || !std::isfinite(value) || std::abs(value) >= 3e38) {
        throw InputError(place + ": vertex coordinate " + std::to_string(axis + 1) + " is not a finite number: '" +
                         token + "'");
      }
    }
  }
}

// Whether tinyobjloader reads the line as a skin weight: "vw" and a space or tab after leading spaces and tabs.
bool IsSkinWeightLine(const std::string& line) {
  const std::size_t start = line.find_first_not_of(" \t");
  return start != std::string::npos && line.compare(start, 2, "vw") == 0 && start + 2 < line.size() &&
         (line[start + 2] == ' ' || line[start + 2] == '\t');
}

// The text tinyobjloader parses: the file's lines, skin weights blanked. hpsf ignores them, and tinyobjloader's own
// number parser turns some tokens that strtod reads as 0 (such as 00e3848364: 0 times 10^3848364) into NaN, which
// it then converts to an int (undefined; found by fuzz_obj). A blank line keeps the line numbers of its errors.
std::string TextWithoutSkinWeights(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text.append(IsSkinWeightLine(line) ? std::string() : line).append("\n");
  return text;
}

}  // namespace

std::vector<ObjTriangle> LoadObjTriangles(const std::string& path) {
  const std::vector<std::string> lines = ObjLines(path);
  CheckLines(path, lines);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // No material library: hpsf takes only the triangles from a mesh (materials come from the scene file).
  if (!reader.ParseFromString(TextWithoutSkinWeights(lines), "", config))
    throw InputError(path + ": " + reader.Error());
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  std::vector<ObjTriangle> triangles;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    for (std::size_t face = 0; face + 2 < indices.size(); face += 3) {
      ObjTriangle t;
      for (int corner = 0; corner < 3; ++corner) {
        const int index = indices[face + corner].vertex_index;
        // In size_t: 3 * index overflows int for an index past 2^31 / 3.
        const std::size_t v = 3 * std::size_t(index);
        if (index < 0 || v + 2 >= attrib.vertices.size()) {
          throw InputError(path + ": face " + std::to_string(face / 3 + 1) + " of shape '" + shape.name +
                           "' refers to a missing vertex");
        }
        t.p[corner] = glm::dvec3(attrib.vertices[v], attrib.vertices[v + 1], attrib.vertices[v + 2]);
      }
      triangles.push_back(t);
    }
  }
  if (triangles.empty()) throw InputError(path + ": the mesh has no faces");
  return triangles;
}

}  // namespace hpsf
