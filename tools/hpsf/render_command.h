// `hpsf render SCENE -o OUT.exr`: trace a scene into records, filter them, write the image.
#ifndef HPSF_TOOLS_HPSF_RENDER_COMMAND_H
#define HPSF_TOOLS_HPSF_RENDER_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

void AddRenderCommand(CLI::App& app, CommandContext& context);
void AddReplayCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_RENDER_COMMAND_H
