// NearNyquistShare: how much of a view's texture lies near its sampling limit.
#include "lfcam/depth/view_sharpness.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace lfcam {
namespace {

// A random pattern of squares `cell` samples wide, each sample the mean over its area of
// `rays` x `rays` points (a box over the pixel, as a render with that many rays a pixel).
cv::Mat BoxSampledSquares(int size, double cell, int rays) {
  cv::RNG rng(7);
  const int cells = int(std::ceil(size / cell)) + 1;
  cv::Mat levels(cells, cells, CV_8UC1);
  rng.fill(levels, cv::RNG::UNIFORM, 0, 2);
  cv::Mat image(size, size, CV_8UC3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      double sum = 0;
      for (int j = 0; j < rays; ++j)
        for (int i = 0; i < rays; ++i) {
          // Squares offset by a third of a sample, so that their edges fall inside samples.
          const double u = (x + (i + 0.5) / rays + 0.33) / cell;
          const double v = (y + (j + 0.5) / rays + 0.33) / cell;
          sum += levels.at<std::uint8_t>(int(v), int(u)) ? 230.0 : 20.0;
        }
      const auto value = cv::saturate_cast<std::uint8_t>(sum / (rays * rays));
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(value, value, value);
    }
  return image;
}

TEST(NearNyquistShare, IsHighForEdgesSharperThanTheSamplingAndLowOnceBlurred) {
  const cv::Mat sharp = BoxSampledSquares(256, 3.3, 3);
  cv::Mat blurred;
  cv::GaussianBlur(sharp, blurred, {0, 0}, 0.8);
  const double sharp_share = NearNyquistShare(sharp), blurred_share = NearNyquistShare(blurred);
  // The real light fields in ../shared/data measure 0.005-0.016 and the sweep reads views above
  // 0.025 through a Gaussian (depth/cost_volume.cpp; docs/depth.md, "Sharp views").
  EXPECT_GT(sharp_share, 0.025);
  EXPECT_LT(blurred_share, 0.01);
  // A grey image, and one in a single channel, the same way.
  cv::Mat grey;
  cv::cvtColor(sharp, grey, cv::COLOR_RGB2GRAY);
  EXPECT_NEAR(NearNyquistShare(grey), sharp_share, 1e-6);
}

TEST(NearNyquistShare, IsZeroWithoutTextureOrSamples) {
  EXPECT_EQ(NearNyquistShare(cv::Mat(64, 64, CV_8UC3, cv::Scalar(90, 90, 90))), 0.0);
  EXPECT_EQ(NearNyquistShare(cv::Mat(8, 8, CV_8UC3, cv::Scalar(0, 0, 0))), 0.0);
  EXPECT_EQ(NearNyquistShare(cv::Mat()), 0.0);
}

}  // namespace
}  // namespace lfcam
