// Scene files: JSON with quads, boxes and OBJ meshes (tinyobjloader), and the built-in scenes. Every error
// names the file and the place in it (a JSON pointer, an OBJ line) and is an InputError: exit code 3.
#ifndef HPSF_TRACER_SCENE_FILE_H
#define HPSF_TRACER_SCENE_FILE_H

#include <string>
#include <vector>

#include "tracer/scene.h"

namespace hpsf {

// Parses scene JSON; `source` names it in messages, `directory` resolves relative mesh paths.
Scene ParseScene(const std::string& json_text, const std::string& source, const std::string& directory);
Scene LoadSceneFile(const std::string& path);

// cornell, furnace, cornell-far-1e5, cornell-far-1e7, cornell-tiny, cornell-zero-red.
const std::vector<std::string>& BuiltinSceneNames();
// A built-in name or a path to a scene file.
Scene LoadScene(const std::string& name_or_path);

}  // namespace hpsf

#endif  // HPSF_TRACER_SCENE_FILE_H
