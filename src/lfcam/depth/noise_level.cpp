#include "lfcam/depth/noise_level.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam {

double NoiseLevel(const cv::Mat& rgb8, double flattest_share) {
  if (rgb8.depth() != CV_8U) throw Error("NoiseLevel: the image must be 8-bit");
  if (rgb8.cols < 3 || rgb8.rows < 3) return 0.0;
  const cv::Mat laplacians = (cv::Mat_<float>(3, 3) << 1, -2, 1, -2, 4, -2, 1, -2, 1);
  std::vector<cv::Mat> channels;
  cv::split(rgb8, channels);
  const cv::Rect inner(1, 1, rgb8.cols - 2, rgb8.rows - 2);
  double sum = 0;
  for (const cv::Mat& channel : channels) {
    cv::Mat f, response, gx, gy, magnitude;
    channel.convertTo(f, CV_32F);
    cv::filter2D(f, response, CV_32F, laplacians);
    cv::Sobel(f, gx, CV_32F, 1, 0);
    cv::Sobel(f, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, magnitude);
    // The samples whose gradient is among the smallest `flattest_share` (the frame's outer
    // samples left out: the filters repeat the edge there).
    std::vector<float> sorted;
    sorted.reserve(std::size_t(inner.area()));
    for (int y = inner.y; y < inner.br().y; ++y)
      for (int x = inner.x; x < inner.br().x; ++x) sorted.push_back(magnitude.at<float>(y, x));
    const std::size_t k =
        std::min(sorted.size() - 1,
                 std::size_t(std::clamp(flattest_share, 0.0, 1.0) * double(sorted.size())));
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    const float threshold = sorted[k];
    double total = 0;
    std::size_t count = 0;
    for (int y = inner.y; y < inner.br().y; ++y)
      for (int x = inner.x; x < inner.br().x; ++x)
        if (magnitude.at<float>(y, x) <= threshold) {
          total += std::abs(response.at<float>(y, x));
          ++count;
        }
    // Immerkær: sigma = sqrt(pi / 2) / 6 * mean |response| for white Gaussian noise.
    sum +=
        std::sqrt(std::numbers::pi / 2.0) / 6.0 * total / double(std::max<std::size_t>(1, count));
  }
  return sum / double(channels.size());
}

}  // namespace lfcam
