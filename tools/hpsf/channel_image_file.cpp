#include "tools/hpsf/channel_image_file.h"

#include <filesystem>

#include <OpenImageIO/imageio.h>

#include "core/error.h"

namespace hpsf {

ChannelImage ReadChannelImage(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw InputError(path + ": no such image file");
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path + ": cannot read the image: " + OIIO::geterror());
  if (std::string(in->format_name()) != "openexr") {
    throw InputError(path + ": not an OpenEXR image (it reads as " + std::string(in->format_name()) +
                     "); hpsf diff compares the EXRs hpsf writes, not their previews");
  }
  const OIIO::ImageSpec& spec = in->spec();
  ChannelImage image;
  image.path = path;
  image.width = spec.width;
  image.height = spec.height;
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw InputError(path + ": the image has no pixels");
  for (int c = 0; c < spec.nchannels; ++c) image.channels.push_back(spec.channel_name(c));
  image.values.resize(image.PixelCount() * image.channels.size());
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.values.data())) {
    throw InputError(path + ": cannot read the pixels: " + in->geterror());
  }
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind("hpsf:", 0) == 0) image.metadata[name.substr(5)] = p.get_string();
  }
  return image;
}

}  // namespace hpsf
