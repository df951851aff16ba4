// Images out: an OpenEXR file with hpsf: metadata and an sRGB PNG preview beside it. Both are written to
// temporary names and renamed only when both succeeded, so a failure leaves no partial output.
#ifndef HPSF_TOOLS_HPSF_IMAGE_FILE_H
#define HPSF_TOOLS_HPSF_IMAGE_FILE_H

#include <map>
#include <span>
#include <string>

#include "core/image.h"

namespace hpsf {

// A named image of the same size riding in the EXR beside R, G, B as NAME.R, NAME.G, NAME.B.
struct ImageLayer {
  std::string name;
  const Image* image = nullptr;
};

// Writes `exr_path` (must end in .exr) and the preview with the extension replaced by .png; returns the
// preview's path. metadata keys are stored as "hpsf:<key>". Each layer (the same size as the image) adds three
// channels after R, G, B, in the order given (`--variance`: variance, then tile_variance); the preview stays the image.
std::string WriteImageFiles(const std::string& exr_path, const Image& image,
                            const std::map<std::string, std::string>& metadata,
                            std::span<const ImageLayer> layers = {});

// Copies an EXR written by WriteImageFiles and its preview to `to_exr` (and its .png), under temporary names
// renamed into place, as WriteImageFiles writes; returns to_exr.
std::string CopyImageFiles(const std::string& from_exr, const std::string& to_exr);

// Reads an EXR written by hpsf (tests, diffs).
Image ReadExr(const std::string& path, std::map<std::string, std::string>* metadata = nullptr);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_IMAGE_FILE_H
