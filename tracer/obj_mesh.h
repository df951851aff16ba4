// Triangles of an OBJ mesh through tinyobjloader, with the checks a scene needs: the file exists, parses, and
// every vertex coordinate is a finite number (tinyobjloader would read "nan" as 0 without a word).
#ifndef HPSF_TRACER_OBJ_MESH_H
#define HPSF_TRACER_OBJ_MESH_H

#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace hpsf {

struct ObjTriangle {
  glm::dvec3 p[3];
};

std::vector<ObjTriangle> LoadObjTriangles(const std::string& path);

}  // namespace hpsf

#endif  // HPSF_TRACER_OBJ_MESH_H
