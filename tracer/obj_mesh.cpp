#include "tracer/obj_mesh.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

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
// skin weights ("vw"), but tinyobjloader converts their joint ids to int unchecked (undefined beyond int range).
void CheckLines(const std::string& path) {
  const std::vector<std::string> lines = ObjLines(path);
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
        throw InputError(place + ": vertex coordinate " + std::to_string(axis + 1) + " is not a finite number: '" + token + "'");
      }
    }
  }
}

}  // namespace

std::vector<ObjTriangle> LoadObjTriangles(const std::string& path) {
  CheckLines(path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) throw InputError(path + ": " + reader.Error());
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
