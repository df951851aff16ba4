// Images out: an OpenEXR file with hpsf: metadata and an sRGB PNG preview beside it. Both are written to
// temporary names and renamed only when both succeeded, so a failure leaves no partial output.
#ifndef HPSF_TOOLS_HPSF_IMAGE_FILE_H
#define HPSF_TOOLS_HPSF_IMAGE_FILE_H

#include <map>
#include <string>

#include "core/image.h"

namespace hpsf {

// Writes `exr_path` (must end in .exr) and the preview with the extension replaced by .png; returns the
// preview's path. metadata keys are stored as "hpsf:<key>". With a variance image (the same size), the EXR gets
// three more channels after R, G, B: variance.R, variance.G, variance.B; the preview stays the image.
std::string WriteImageFiles(const std::string& exr_path, const Image& image,
                            const std::map<std::string, std::string>& metadata, const Image* variance = nullptr);

// Copies an EXR written by WriteImageFiles and its preview to `to_exr` (and its .png), under temporary names
// renamed into place, as WriteImageFiles writes; returns to_exr.
std::string CopyImageFiles(const std::string& from_exr, const std::string& to_exr);

// Reads an EXR written by hpsf (tests, diffs).
Image ReadExr(const std::string& path, std::map<std::string, std::string>* metadata = nullptr);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_IMAGE_FILE_H
