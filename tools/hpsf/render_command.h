// `hpsf render SCENE -o OUT.exr`: trace a scene into records, filter them, write the image.
#ifndef HPSF_TOOLS_HPSF_RENDER_COMMAND_H
#define HPSF_TOOLS_HPSF_RENDER_COMMAND_H

#include <CLI/CLI.hpp>

namespace hpsf {

void AddRenderCommand(CLI::App& app);
void AddReplayCommand(CLI::App& app);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_RENDER_COMMAND_H
