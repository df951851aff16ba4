// The plain metrics of `hpsf diff` and its verdict rule on constructed images whose answers are known by hand,
// and RMSE, PSNR, the mean and the maximum error (with its place) against OpenImageIO's own comparison, the code
// behind `idiff` and `oiiotool --diff`, on two real renders.
#include "verifier/metrics/image_metrics.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <regex>
#include <string>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "property_tests/traced_batch.h"
#include "reference/reference_filter.h"
#include "verifier/metrics/diff_verdict.h"
#include "verifier/metrics/image_comparison.h"
#include "verifier/metrics/srgb.h"
#include "verifier/metrics/ssim.h"

namespace hpsf {
namespace {

ChannelImage Constant(int width, int height, float value, std::vector<std::string> channels = {"R", "G", "B"}) {
  ChannelImage image;
  image.path = "constant.exr";
  image.width = width;
  image.height = height;
  image.channels = std::move(channels);
  image.values.assign(image.PixelCount() * image.channels.size(), value);
  return image;
}

float& At(ChannelImage& image, int x, int y, int channel) {
  return image.values[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * image.channels.size() + channel];
}

ChannelImage FromImage(const Image& image, const std::string& path) {
  ChannelImage c = Constant(int(image.width), int(image.height), 0.0f);
  c.path = path;
  for (std::size_t p = 0; p < image.pixels.size(); ++p) {
    for (int k = 0; k < 3; ++k) c.values[p * 3 + k] = image.pixels[p][k];
  }
  return c;
}

// 2x2 RGB, B all 1; A differs by 0.5 at (1, 0) in G and by -0.25 at (0, 1) in B: 12 values, two of them off.
TEST(ImageMetrics, KnownAnswersOnAConstructedPair) {
  const ChannelImage b = Constant(2, 2, 1.0f);
  ChannelImage a = b;
  At(a, 1, 0, 1) = 1.5f;
  At(a, 0, 1, 2) = 0.75f;
  MetricOptions options;
  options.percentile = 90.0;      // rank ceil(0.9 * 12) = 11 of 12: the smaller of the two errors
  options.pixel_threshold = 0.3;  // only the pixel off by 0.5 is over it
  const ImageMetrics m = ComputeMetrics(a, b, options);
  EXPECT_EQ(m.values, 12u);
  EXPECT_DOUBLE_EQ(m.mse, (0.25 + 0.0625) / 12.0);
  EXPECT_DOUBLE_EQ(m.rmse, std::sqrt((0.25 + 0.0625) / 12.0));
  EXPECT_DOUBLE_EQ(m.relmse, (0.25 / 1.01 + 0.0625 / 1.01) / 12.0);
  EXPECT_DOUBLE_EQ(m.peak, 1.5);
  EXPECT_DOUBLE_EQ(m.psnr, 20.0 * std::log10(1.5 / m.rmse));
  EXPECT_DOUBLE_EQ(m.mean_abs, 0.75 / 12.0);
  EXPECT_DOUBLE_EQ(m.max_abs, 0.5);
  EXPECT_EQ(m.max_x, 1);
  EXPECT_EQ(m.max_y, 0);
  EXPECT_EQ(m.max_channel, "G");
  EXPECT_DOUBLE_EQ(m.percentile, 0.25);
  EXPECT_DOUBLE_EQ(m.fraction_over, 0.25);
  options.percentile = 100.0;
  EXPECT_DOUBLE_EQ(ComputeMetrics(a, b, options).percentile, 0.5);
  options.percentile = 50.0;
  EXPECT_DOUBLE_EQ(ComputeMetrics(a, b, options).percentile, 0.0);
}

TEST(ImageMetrics, IdenticalImagesHaveNoErrorAndInfinitePsnr) {
  const ChannelImage a = Constant(3, 2, 0.25f);
  const ImageMetrics m = ComputeMetrics(a, a);
  EXPECT_EQ(m.mse, 0.0);
  EXPECT_EQ(m.max_abs, 0.0);
  EXPECT_TRUE(std::isinf(m.psnr));
  EXPECT_EQ(m.peak, 1.0);  // values below 1: idiff's peak of 1
  EXPECT_EQ(ToJson(m)["psnr"], nullptr);
}

// relMSE divides by the reference B, not by A: swapping them changes it.
TEST(ImageMetrics, RelMseIsRelativeToTheReference) {
  const ChannelImage b = Constant(1, 1, 0.1f, {"Y"});
  const ChannelImage a = Constant(1, 1, 0.2f, {"Y"});
  const double d2 = (double(0.2f) - double(0.1f)) * (double(0.2f) - double(0.1f));
  EXPECT_NEAR(ComputeMetrics(a, b).relmse, d2 / (double(0.1f) * double(0.1f) + 0.01), 1e-9);
  EXPECT_NEAR(ComputeMetrics(b, a).relmse, d2 / (double(0.2f) * double(0.2f) + 0.01), 1e-9);
}

// The first of equal maxima in pixel order wins, so the place reported does not depend on anything but the images.
TEST(ImageMetrics, TheFirstOfEqualMaximaIsReported) {
  const ChannelImage b = Constant(3, 3, 0.0f);
  ChannelImage a = b;
  At(a, 2, 2, 0) = 1.0f;
  At(a, 1, 1, 2) = 1.0f;
  const ImageMetrics m = ComputeMetrics(a, b);
  EXPECT_EQ(m.max_x, 1);
  EXPECT_EQ(m.max_y, 1);
  EXPECT_EQ(m.max_channel, "B");
}

TEST(ImageMetrics, NonFiniteValuesMatchOnlyThemselves) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  ChannelImage b = Constant(2, 2, 1.0f);
  At(b, 0, 0, 0) = nan;
  At(b, 1, 0, 0) = inf;
  At(b, 0, 1, 0) = inf;
  ChannelImage a = b;
  EXPECT_EQ(ComputeMetrics(a, b).nonfinite_mismatches, 0u);  // NaN against NaN, Inf against Inf
  EXPECT_EQ(ComputeMetrics(a, b).values, 9u);
  At(a, 0, 0, 0) = 1.0f;  // a number against NaN
  At(a, 0, 1, 0) = -inf;  // -Inf against +Inf
  const ImageMetrics m = ComputeMetrics(a, b);
  EXPECT_EQ(m.nonfinite_mismatches, 2u);
  EXPECT_EQ(m.max_abs, 0.0);  // they enter no other metric
  EXPECT_EQ(Judge(m, 1.0, DiffThresholds{DiffMetric::kMaxAbs, 1.0, 2.0}), DiffVerdict::kFail);
}

// Variance channels are the statistical comparison's, not a colour to diff.
TEST(ImageMetrics, VarianceChannelsAreNotCompared) {
  const std::vector<std::string> channels = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
  const ChannelImage b = Constant(2, 2, 1.0f, channels);
  ChannelImage a = b;
  At(a, 0, 0, 4) = 7.0f;
  const ImageMetrics m = ComputeMetrics(a, b);
  EXPECT_EQ(m.values, 12u);
  EXPECT_EQ(m.max_abs, 0.0);
}

TEST(ImageMetrics, ImagesOfDifferentShapeAreBadInputNamingBothFiles) {
  ChannelImage a = Constant(2, 2, 0.0f), b = Constant(2, 3, 0.0f), c = Constant(2, 2, 0.0f, {"R", "G", "B", "A"});
  a.path = "a.exr";
  b.path = "b.exr";
  c.path = "c.exr";
  try {
    ComputeMetrics(a, b);
    FAIL() << "a size mismatch was compared";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a.exr is 2x2 [R,G,B], b.exr is 2x3 [R,G,B]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ComputeMetrics(a, c), InputError);
}

// The written rule: FAIL above --fail, WARN above --warn only (where idiff says PASS), PASS otherwise; for PSNR
// and SSIM, smaller is worse.
TEST(DiffVerdict, TheWrittenRule) {
  ImageMetrics m;
  m.max_abs = 0.5;
  EXPECT_EQ(Judge(m, 1.0, {DiffMetric::kMaxAbs, 0.1, 1.0}), DiffVerdict::kWarn);
  EXPECT_EQ(Judge(m, 1.0, {DiffMetric::kMaxAbs, 0.1, 0.4}), DiffVerdict::kFail);
  EXPECT_EQ(Judge(m, 1.0, {DiffMetric::kMaxAbs, 0.5, 0.5}), DiffVerdict::kPass);  // not above: equal passes
  m.psnr = 30.0;
  EXPECT_EQ(Judge(m, 1.0, {DiffMetric::kPsnr, 40.0, 20.0}), DiffVerdict::kWarn);
  EXPECT_EQ(Judge(m, 1.0, {DiffMetric::kPsnr, 50.0, 35.0}), DiffVerdict::kFail);
  EXPECT_EQ(Judge(m, 1.0, {DiffMetric::kPsnr, 30.0, 20.0}), DiffVerdict::kPass);
  EXPECT_EQ(Judge(m, 0.9, {DiffMetric::kSsim, 0.95, 0.8}), DiffVerdict::kWarn);
  EXPECT_EQ(ExitCode(DiffVerdict::kPass), 0);
  EXPECT_EQ(ExitCode(DiffVerdict::kWarn), 1);
  EXPECT_EQ(ExitCode(DiffVerdict::kFail), 2);
  for (const std::string& name : DiffMetricNames()) EXPECT_EQ(ToString(ParseDiffMetric(name)), name);
  EXPECT_THROW(ParseDiffMetric("flip"), ConfigError);
}

// For constant images SSIM has a closed form: the variances vanish, leaving the luminance term
// (2 mu_a mu_b + C1) / (mu_a^2 + mu_b^2 + C1) with C1 = (0.01 * 255)^2, on the sRGB-encoded values times 255.
TEST(Ssim, ConstantImagesHaveTheClosedForm) {
  const ChannelImage a = Constant(16, 16, 0.2f), b = Constant(16, 16, 0.5f);
  const double mu_a = 255.0 * EncodeSrgb(0.2f), mu_b = 255.0 * EncodeSrgb(0.5f), c1 = 6.5025;
  EXPECT_NEAR(SrgbSsim(a, b), (2.0 * mu_a * mu_b + c1) / (mu_a * mu_a + mu_b * mu_b + c1), 1e-6);
  EXPECT_NEAR(SrgbSsim(a, a), 1.0, 1e-12);
}

// OpenImageIO's compare (idiff, oiiotool --diff) on two renders of the Cornell box with different seeds: the
// mean, RMS and maximum errors, the place of the maximum and the PSNR agree to 1e-6 relative.
TEST(ImageMetrics, AgreeWithOpenImageIoOnRealRenders) {
  const Image first = ReferenceFilter(testing::TracedBatch("cornell", 48, 2), FilterConfig{}).image;
  TraceOptions trace;
  trace.width = trace.height = 48;
  trace.samples_per_pixel = 2;
  trace.seed = 2;
  const Image second = ReferenceFilter(TraceRecords(LoadScene("cornell"), trace).batch, FilterConfig{}).image;
  const ChannelImage a = FromImage(first, "a.exr"), b = FromImage(second, "b.exr");
  const ImageMetrics m = ComputeMetrics(a, b);

  OIIO::ImageBuf oa(OIIO::ImageSpec(48, 48, 3, OIIO::TypeDesc::FLOAT), const_cast<float*>(a.values.data()));
  OIIO::ImageBuf ob(OIIO::ImageSpec(48, 48, 3, OIIO::TypeDesc::FLOAT), const_cast<float*>(b.values.data()));
  const OIIO::ImageBufAlgo::CompareResults oiio = OIIO::ImageBufAlgo::compare(oa, ob, 1e9f, 1e9f);
  ASSERT_FALSE(oiio.error);
  ASSERT_GT(m.max_abs, 0.01);
  auto relative = [](double x, double y) { return std::abs(x - y) / std::abs(y); };
  EXPECT_LT(relative(m.mean_abs, oiio.meanerror), 1e-6) << m.mean_abs << " vs " << oiio.meanerror;
  EXPECT_LT(relative(m.rmse, oiio.rms_error), 1e-6) << m.rmse << " vs " << oiio.rms_error;
  EXPECT_LT(relative(m.psnr, oiio.PSNR), 1e-6) << m.psnr << " vs " << oiio.PSNR;
  EXPECT_LT(relative(m.max_abs, oiio.maxerror), 1e-6) << m.max_abs << " vs " << oiio.maxerror;
  EXPECT_EQ(m.max_x, oiio.maxx);
  EXPECT_EQ(m.max_y, oiio.maxy);
  EXPECT_EQ(m.max_channel, a.channels[std::size_t(oiio.maxc)]);
  std::printf(
      "cornell 48x48, seeds 1 and 2: hpsf rmse %.9g psnr %.9g max %.9g at (%d, %d, %s); OpenImageIO "
      "rmse %.9g psnr %.9g max %.9g at (%d, %d, %d)\n",
      m.rmse, m.psnr, m.max_abs, m.max_x, m.max_y, m.max_channel.c_str(), oiio.rms_error, oiio.PSNR,
      double(oiio.maxerror), oiio.maxx, oiio.maxy, oiio.maxc);
}

void WriteExr(const std::string& path, const ChannelImage& image) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, image.values.data()) && out->close());
}

// The idiff program itself on the same two renders written as EXRs: it prints six significant digits, so its
// figures agree with hpsf's to within half a unit of the sixth digit (5e-6 relative).
TEST(ImageMetrics, AgreeWithTheIdiffProgram) {
  TraceOptions trace;
  trace.width = trace.height = 40;
  trace.samples_per_pixel = 2;
  const ChannelImage a = FromImage(ReferenceFilter(TraceRecords(LoadScene("cornell"), trace).batch, {}).image, "a");
  trace.seed = 3;
  const ChannelImage b = FromImage(ReferenceFilter(TraceRecords(LoadScene("cornell"), trace).batch, {}).image, "b");
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("hpsf_idiff_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  WriteExr((dir / "a.exr").string(), a);
  WriteExr((dir / "b.exr").string(), b);
  const std::string command =
      "idiff -v -fail 1e9 -warn 1e9 " + (dir / "a.exr").string() + " " + (dir / "b.exr").string();
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string printed;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe)) printed += buffer;
  pclose(pipe);
  std::smatch mean, rms, psnr, max;
  ASSERT_TRUE(std::regex_search(printed, mean, std::regex("Mean error = ([0-9.e+-]+)"))) << printed;
  ASSERT_TRUE(std::regex_search(printed, rms, std::regex("RMS error = ([0-9.e+-]+)"))) << printed;
  ASSERT_TRUE(std::regex_search(printed, psnr, std::regex("Peak SNR = ([0-9.e+-]+)"))) << printed;
  ASSERT_TRUE(std::regex_search(printed, max, std::regex("Max error  = ([0-9.e+-]+) @ \\(([0-9]+), ([0-9]+), ([A-Z])")))
      << printed;
  const ImageMetrics m = ComputeMetrics(a, b);
  auto relative = [](double x, const std::string& printed_value) {
    const double y = std::stod(printed_value);
    return std::abs(x - y) / std::abs(y);
  };
  EXPECT_LT(relative(m.mean_abs, mean[1]), 5e-6) << printed;
  EXPECT_LT(relative(m.rmse, rms[1]), 5e-6) << printed;
  EXPECT_LT(relative(m.psnr, psnr[1]), 5e-6) << printed;
  EXPECT_LT(relative(m.max_abs, max[1]), 5e-6) << printed;
  EXPECT_EQ(std::to_string(m.max_x), max[2].str());
  EXPECT_EQ(std::to_string(m.max_y), max[3].str());
  EXPECT_EQ(m.max_channel, max[4].str());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace hpsf
