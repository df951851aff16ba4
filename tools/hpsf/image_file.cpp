#include "tools/hpsf/image_file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "core/error.h"
#include "verifier/metrics/srgb.h"

namespace hpsf {
namespace {

void Write(const std::string& path, const OIIO::ImageSpec& spec, const void* data, const std::string& shown_as) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, spec) || !out->write_image(spec.format, data) || !out->close()) {
    throw InputError(shown_as + ": cannot write the image: " + (out ? out->geterror() : OIIO::geterror()));
  }
}

void CopyHpsfMetadata(const OIIO::ImageSpec& spec, std::map<std::string, std::string>& metadata) {
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind("hpsf:", 0) == 0) metadata[name.substr(5)] = p.get_string();
  }
}

}  // namespace

std::string WriteImageFiles(const std::string& exr_path, const Image& image,
                            const std::map<std::string, std::string>& metadata, std::span<const ImageLayer> layers) {
  const std::filesystem::path exr(exr_path);
  if (exr.extension() != ".exr") throw InputError(exr_path + ": the output must be an .exr file");
  const std::filesystem::path png = std::filesystem::path(exr).replace_extension(".png");
  // Temporary names keep their extension, which tells OpenImageIO the format.
  // The names are appended in place: GCC 12 at -O3 reports a false -Wrestrict on "literal" + std::string&&
  // (GCC bug 105651).
  const std::string hidden_stem = std::string(".").append(exr.stem().string());
  const std::filesystem::path exr_temporary = exr.parent_path() / (hidden_stem + ".partial.exr");
  const std::filesystem::path png_temporary = exr.parent_path() / (hidden_stem + ".partial.png");

  // OpenEXR writes chunks in the order its threads finish them; one thread makes the file bytes, not only the
  // pixels, the same on every run, so files can be compared as files.
  OIIO::attribute("exr_threads", 1);
  std::vector<const Image*> planes{&image};
  std::vector<std::string> names{"R", "G", "B"};
  for (const ImageLayer& layer : layers) {
    if (layer.image->width != image.width || layer.image->height != image.height) {
      throw std::invalid_argument(exr_path + ": the " + layer.name + " image's size differs from the image's");
    }
    planes.push_back(layer.image);
    for (const char* c : {".R", ".G", ".B"}) names.push_back(layer.name + c);
  }
  OIIO::ImageSpec spec(int(image.width), int(image.height), int(names.size()), OIIO::TypeDesc::FLOAT);
  // The layers ride in the same file, by channel name, so the image and its noise cannot be separated.
  spec.channelnames = names;
  std::vector<float> channels;  // interleaved only when there are layers: the plain image is written in place
  if (!layers.empty()) channels.reserve(image.pixels.size() * names.size());
  for (std::size_t i = 0; i < image.pixels.size() && !layers.empty(); ++i) {
    for (const Image* plane : planes) {
      const glm::vec3& v = plane->pixels[i];
      channels.insert(channels.end(), {v.x, v.y, v.z});
    }
  }
  for (const auto& [key, value] : metadata) spec.attribute("hpsf:" + key, value);
  // No timestamp either (OpenEXR's capDate): the same render gives the same file.
  spec.attribute("DateTime", "");
  std::vector<std::uint8_t> preview(image.pixels.size() * 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) preview[3 * i + c] = EncodeSrgb8(image.pixels[i][c]);
  }
  OIIO::ImageSpec preview_spec(int(image.width), int(image.height), 3, OIIO::TypeDesc::UINT8);
  std::error_code created;
  if (!exr.parent_path().empty()) std::filesystem::create_directories(exr.parent_path(), created);
  // Both files are written under temporary names, then renamed; a failure at any step removes whatever this
  // call created, the EXR already renamed into place included, so no output is left half made.
  bool exr_placed = false;
  try {
    const void* pixels = layers.empty() ? static_cast<const void*>(image.pixels.data()) : channels.data();
    Write(exr_temporary.string(), spec, pixels, exr_path);
    Write(png_temporary.string(), preview_spec, preview.data(), png.string());
    std::error_code failed;
    std::filesystem::rename(exr_temporary, exr, failed);
    if (failed) throw InputError(exr_path + ": cannot put the image in place: " + failed.message());
    exr_placed = true;
    std::filesystem::rename(png_temporary, png, failed);
    if (failed) throw InputError(png.string() + ": cannot put the preview in place: " + failed.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(exr_temporary, ignored);
    std::filesystem::remove(png_temporary, ignored);
    if (exr_placed) std::filesystem::remove(exr, ignored);
    throw;
  }
  return png.string();
}

std::string CopyImageFiles(const std::string& from_exr, const std::string& to_exr) {
  namespace fs = std::filesystem;
  const fs::path to(to_exr);
  if (to.extension() != ".exr") throw InputError(to_exr + ": the output must be an .exr file");
  std::error_code created;
  if (!to.parent_path().empty()) fs::create_directories(to.parent_path(), created);
  const std::string hidden_stem = std::string(".").append(to.stem().string());
  std::vector<fs::path> placed;
  try {
    for (const char* extension : {".exr", ".png"}) {
      const fs::path from = fs::path(from_exr).replace_extension(extension);
      const fs::path target = fs::path(to).replace_extension(extension);
      const fs::path temporary = to.parent_path() / (hidden_stem + ".partial" + extension);
      std::error_code failed;
      fs::copy_file(from, temporary, fs::copy_options::overwrite_existing, failed);
      if (!failed) fs::rename(temporary, target, failed);
      if (failed) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw InputError(target.string() + ": cannot write the copy of " + from.string() + ": " + failed.message());
      }
      placed.push_back(target);
    }
  } catch (...) {
    std::error_code ignored;
    for (const fs::path& p : placed) fs::remove(p, ignored);
    throw;
  }
  return to_exr;
}

Image ReadExr(const std::string& path, std::map<std::string, std::string>* metadata) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path + ": cannot read the image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels < 3) throw InputError(path + ": expected an RGB image");
  Image image(std::uint32_t(spec.width), std::uint32_t(spec.height));
  std::vector<float> data(std::size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data())) {
    throw InputError(path + ": cannot read the pixels: " + in->geterror());
  }
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = glm::vec3(data[i * spec.nchannels], data[i * spec.nchannels + 1], data[i * spec.nchannels + 2]);
  }
  if (metadata) CopyHpsfMetadata(spec, *metadata);
  return image;
}

}  // namespace hpsf
