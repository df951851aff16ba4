// The EXR's variance channels (`--variance`) as the statistical comparison reads them back (ReadChannelImage, then
// ToNoisyImage): by name, exactly, and with a clear error naming the file and what is missing when a file has none.
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tools/checks/statistical_compare.h"
#include "tools/hpsf/channel_image_file.h"
#include "tools/hpsf/image_file.h"

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

TEST(ImageFile, VarianceChannelsRoundTripByName) {
  const std::string path = Path("image_file_variance.exr");
  const Image image = Ramp(1.0f), variance = Ramp(0.01f);
  WriteImageFiles(path, image, {{"mean_variance", "0.25 1.0000000000000002 3e-300"}, {"spp", "4"}}, &variance);
  const ChannelImage file = ReadChannelImage(path);
  const std::map<std::string, std::string>& metadata = file.metadata;
  const NoisyImage read = ToNoisyImage(file);
  EXPECT_TRUE(SameBits(read.mean, image));
  EXPECT_TRUE(SameBits(read.variance, variance));
  EXPECT_EQ(read.mean_variance, glm::dvec3(0.25, 1.0000000000000002, 3e-300));
  EXPECT_EQ(metadata.at("spp"), "4");
  // The plain reader still finds R, G, B first.
  EXPECT_TRUE(SameBits(ReadExr(path), image));
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
  const Image variance = Ramp(0.01f);
  WriteImageFiles(path, Ramp(1.0f), {{"spp", "4"}}, &variance);
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

}  // namespace
}  // namespace hpsf
