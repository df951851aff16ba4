#include "tracer/obj_mesh.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <tiny_obj_loader.h>

#include "core/error.h"

namespace hpsf {
namespace {

// Every "v" line must hold three finite numbers; tinyobjloader silently turns unparsable ones into 0.
void CheckVertexLines(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the mesh file");
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream tokens(line);
    std::string tag;
    if (!(tokens >> tag) || tag != "v") continue;
    for (int axis = 0; axis < 3; ++axis) {
      std::string token;
      tokens >> token;
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (token.empty() || *end != '\0' || !std::isfinite(value) || std::abs(value) >= 3e38) {
        throw InputError(path + ":" + std::to_string(number) + ": vertex coordinate " + std::to_string(axis + 1) +
                         " is not a finite number: '" + token + "'");
      }
    }
  }
}

}  // namespace

std::vector<ObjTriangle> LoadObjTriangles(const std::string& path) {
  CheckVertexLines(path);
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
        const int v = indices[face + corner].vertex_index;
        if (v < 0 || std::size_t(3 * v + 2) >= attrib.vertices.size()) {
          throw InputError(path + ": face " + std::to_string(face / 3 + 1) + " of shape '" + shape.name +
                           "' refers to a missing vertex");
        }
        t.p[corner] = glm::dvec3(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
      }
      triangles.push_back(t);
    }
  }
  if (triangles.empty()) throw InputError(path + ": the mesh has no faces");
  return triangles;
}

}  // namespace hpsf
