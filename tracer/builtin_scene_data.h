// The built-in scene files (scenes/*.json), compiled into the program so a built-in name works anywhere.
#ifndef HPSF_TRACER_BUILTIN_SCENE_DATA_H
#define HPSF_TRACER_BUILTIN_SCENE_DATA_H

namespace hpsf {

extern const char* const kCornellSceneJson;
extern const char* const kFurnaceSceneJson;

}  // namespace hpsf

#endif  // HPSF_TRACER_BUILTIN_SCENE_DATA_H
