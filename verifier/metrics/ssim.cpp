#include "verifier/metrics/ssim.h"

#include <opencv2/core.hpp>
#include <opencv2/core/ocl.hpp>
#include <opencv2/quality/qualityssim.hpp>

#include "verifier/metrics/image_metrics.h"
#include "verifier/metrics/srgb.h"

namespace hpsf {
namespace {

cv::Mat DisplayedChannel(const ChannelImage& image, std::size_t channel) {
  cv::Mat mat(image.height, image.width, CV_32FC1);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      mat.at<float>(y, x) =
          255.0f * EncodeSrgb(image.At(std::size_t(y) * std::size_t(image.width) + std::size_t(x), channel));
    }
  }
  return mat;
}

}  // namespace

double SrgbSsim(const ChannelImage& a, const ChannelImage& b) {
  CheckComparable(a, b);
  // The quality module works on UMat; without this OpenCV probes for an OpenCL device on the first call.
  cv::ocl::setUseOpenCL(false);
  double sum = 0.0;
  int counted = 0;
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    if (!IsColorChannel(a.channels[c])) continue;
    const cv::Scalar ssim =
        cv::quality::QualitySSIM::compute(DisplayedChannel(b, c), DisplayedChannel(a, c), cv::noArray());
    sum += ssim[0];
    ++counted;
  }
  return counted > 0 ? sum / counted : 1.0;
}

}  // namespace hpsf
