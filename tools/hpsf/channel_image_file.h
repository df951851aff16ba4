// Reading any image `hpsf diff` is given into a ChannelImage: every channel in float, with its hpsf: metadata.
// Only OpenEXR is accepted: a diff of 8-bit previews would judge the tone mapping, not the render.
#ifndef HPSF_TOOLS_HPSF_CHANNEL_IMAGE_FILE_H
#define HPSF_TOOLS_HPSF_CHANNEL_IMAGE_FILE_H

#include <string>

#include "verifier/metrics/channel_image.h"

namespace hpsf {

// Throws InputError naming the file: missing, unreadable, not OpenEXR, or without pixels.
ChannelImage ReadChannelImage(const std::string& path);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_CHANNEL_IMAGE_FILE_H
