// An image as `hpsf diff` compares it: any number of named float channels, interleaved per pixel, row-major from
// the top-left, with the hpsf: metadata of the file it came from. Reading it is the command line's job (through
// OpenImageIO); the checks only see the numbers.
#ifndef HPSF_VERIFIER_METRICS_CHANNEL_IMAGE_H
#define HPSF_VERIFIER_METRICS_CHANNEL_IMAGE_H

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "core/image.h"

namespace hpsf {

struct ChannelImage {
  std::string path;  // where it was read from, for messages
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;            // e.g. R, G, B, variance.R, ...
  std::vector<float> values;                    // width * height * channels.size()
  std::map<std::string, std::string> metadata;  // the hpsf: attributes, without the prefix

  std::size_t PixelCount() const { return std::size_t(width) * std::size_t(height); }
  float At(std::size_t pixel, std::size_t channel) const { return values[pixel * channels.size() + channel]; }
  // The index of a channel by name, or -1.
  int ChannelIndex(const std::string& name) const {
    for (std::size_t c = 0; c < channels.size(); ++c) {
      if (channels[c] == name) return int(c);
    }
    return -1;
  }
};

// The channels the plain metrics compare: every channel but the variance estimate (`variance.*`), which only
// the statistical comparison reads.
inline bool IsColorChannel(const std::string& name) { return name.rfind("variance.", 0) != 0; }

// An in-memory image (a filter's output) as the checks compare it: channels R, G, B, no path, no metadata.
inline ChannelImage ColourChannels(const Image& image) {
  ChannelImage c{"", int(image.width), int(image.height), {"R", "G", "B"}, {}, {}};
  c.values.reserve(image.pixels.size() * 3);
  for (const glm::vec3& p : image.pixels) c.values.insert(c.values.end(), {p.x, p.y, p.z});
  return c;
}

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_CHANNEL_IMAGE_H
