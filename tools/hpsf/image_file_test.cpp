// The EXR's variance channels (`--variance`) as the statistical comparison reads them back (ReadChannelImage, then
// ToNoisyImage): by name, exactly, and with a clear error naming the file and what is missing when a file has none.
#include "tools/hpsf/image_file.h"

#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tools/hpsf/channel_image_file.h"
#include "verifier/metrics/statistical_compare.h"

namespace hpsf {
namespace {

Image Ramp(float scale) {
  Image image(5, 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = scale * glm::vec3(float(i), 0.5f, 1e-7f * float(i));
  }
  return image;
}

std::string Path(const std::string& name) { return (std::filesystem::path(::testing::TempDir()) / name).string(); }

// A tile variance layer for a 5x3 image in tiles of 2: 3x2 tiles, each pixel holding its tile's value.
Image TileLayer() {
  Image layer(5, 3);
  for (std::uint32_t y = 0; y < 3; ++y) {
    for (std::uint32_t x = 0; x < 5; ++x) layer.pixels[y * 5 + x] = glm::vec3(float(y / 2 * 3 + x / 2) * 0.125f);
  }
  return layer;
}

const std::map<std::string, std::string> kNoiseMetadata = {
    {"mean_variance", "0.25 1.0000000000000002 3e-300"}, {"spp", "4"}, {"variance_tile", "2"}};

TEST(ImageFile, VarianceChannelsRoundTripByName) {
  const std::string path = Path("image_file_variance.exr");
  const Image image = Ramp(1.0f), variance = Ramp(0.01f), tiles = TileLayer();
  const ImageLayer layers[] = {{"variance", &variance}, {"tile_variance", &tiles}};
  WriteImageFiles(path, image, kNoiseMetadata, layers);
  const ChannelImage file = ReadChannelImage(path);
  const std::map<std::string, std::string>& metadata = file.metadata;
  const NoisyImage read = ToNoisyImage(file);
  EXPECT_TRUE(SameBits(read.mean, image));
  EXPECT_TRUE(SameBits(read.variance, variance));
  EXPECT_EQ(read.mean_variance, glm::dvec3(0.25, 1.0000000000000002, 3e-300));
  EXPECT_EQ(read.samples_per_pixel, 4u);
  EXPECT_EQ(read.tile_size, 2u);
  ASSERT_EQ(read.tile_variance.width, 3u);
  ASSERT_EQ(read.tile_variance.height, 2u);
  for (std::size_t t = 0; t < 6; ++t) EXPECT_EQ(read.tile_variance.pixels[t], glm::vec3(float(t) * 0.125f)) << t;
  EXPECT_EQ(metadata.at("spp"), "4");
  // The plain reader still finds R, G, B first.
  EXPECT_TRUE(SameBits(ReadExr(path), image));
}

// Variances are read from a file a user hands over: a negative or infinite one, or a tile size that is not a
// positive number, is bad input naming the file and the place.
TEST(ImageFile, AnImpossibleVarianceOrTileIsBadInputNamingTheFile) {
  const Image variance = Ramp(0.01f), tiles = TileLayer();
  Image negative = tiles;
  negative.pixels[4].y = -1.0f;  // pixel (4, 0): the top-left pixel of tile (2, 0), where its value is read
  const ImageLayer bad_tiles[] = {{"variance", &variance}, {"tile_variance", &negative}};
  const std::string path = Path("image_file_negative.exr");
  WriteImageFiles(path, Ramp(1.0f), kNoiseMetadata, bad_tiles);
  try {
    ToNoisyImage(ReadChannelImage(path));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": tile_variance at (4, 0, G)"), std::string::npos) << e.what();
  }
  const ImageLayer layers[] = {{"variance", &variance}, {"tile_variance", &tiles}};
  for (const char* tile : {"0", "-2", "two", "8x"}) {
    std::map<std::string, std::string> metadata = kNoiseMetadata;
    metadata["variance_tile"] = tile;
    const std::string bad = Path("image_file_tile.exr");
    WriteImageFiles(bad, Ramp(1.0f), metadata, layers);
    try {
      ToNoisyImage(ReadChannelImage(bad));
      FAIL() << "no error for variance_tile " << tile;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(bad + ": no attribute 'hpsf:variance_tile'"), std::string::npos) << e.what();
    }
  }
}

TEST(ImageFile, AnExrWithoutVarianceIsBadInputNamingTheChannel) {
  const std::string path = Path("image_file_plain.exr");
  WriteImageFiles(path, Ramp(1.0f), {{"mean_variance", "1 1 1"}});
  try {
    ToNoisyImage(ReadChannelImage(path));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'variance.R'"), std::string::npos) << e.what();
  }
}

TEST(ImageFile, AnExrWithoutTheMeanVarianceIsBadInput) {
  const std::string path = Path("image_file_no_mean.exr");
  const Image variance = Ramp(0.01f), tiles = TileLayer();
  const ImageLayer layers[] = {{"variance", &variance}, {"tile_variance", &tiles}};
  WriteImageFiles(path, Ramp(1.0f), {{"spp", "4"}, {"variance_tile", "2"}}, layers);
  EXPECT_THROW(
      {
        try {
          ToNoisyImage(ReadChannelImage(path));
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("hpsf:mean_variance"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
}

// Every write site fails in turn, made to by a directory where a file must go (a temporary name, then a final
// one), for the EXR and its preview, written and copied. Each failure is an InputError naming the file, and leaves
// neither output nor temporary behind: none of the first, second or later sites may leave a half-made pair.
TEST(ImageFile, AFailureAtAnyWriteSiteLeavesNothingBehind) {
  namespace fs = std::filesystem;
  const fs::path root = Path("write_sites");
  fs::remove_all(root);
  fs::create_directories(root / "source");
  const std::string source = (root / "source" / "in.exr").string();
  WriteImageFiles(source, Ramp(1.0f), {{"spp", "4"}});
  const char* const obstacles[] = {".out.partial.exr", ".out.partial.png", "out.exr", "out.png"};
  for (const bool copying : {false, true}) {
    for (const char* obstacle : obstacles) {
      const fs::path dir = root / (std::string(copying ? "copy-" : "write-") + obstacle);
      fs::create_directories(dir / obstacle / "occupied");
      const std::string out = (dir / "out.exr").string();
      const std::string what = std::string(copying ? "copying" : "writing") + " with a directory at " + obstacle;
      try {
        if (copying) {
          CopyImageFiles(source, out);
        } else {
          WriteImageFiles(out, Ramp(1.0f), {{"spp", "4"}});
        }
        ADD_FAILURE() << what << ": no error";
      } catch (const InputError& e) {
        const std::string message = e.what();
        const std::string named = std::string(obstacle).find("png") != std::string::npos ? "out.png" : "out.exr";
        EXPECT_NE(message.find(named), std::string::npos) << what << ": " << message;
      }
      for (const char* left : obstacles) {
        if (std::string(left) == obstacle) continue;  // the obstacle itself stays
        EXPECT_FALSE(fs::exists(dir / left)) << what << ": " << left << " was left behind";
      }
    }
  }
}

}  // namespace
}  // namespace hpsf
