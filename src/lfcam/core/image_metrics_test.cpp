#include "lfcam/core/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

cv::Mat TestPattern() {
  cv::Mat m(64, 80, CV_8UC3);
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x)
      m.at<cv::Vec3b>(y, x) = cv::Vec3b(uchar((x * 7 + y * 3) % 256), uchar((x ^ y) * 4 % 256),
                                        uchar(((x / 8 + y / 8) % 2) * 200 + 20));
  return m;
}

TEST(CompareImages, IdenticalImagesArePerfect) {
  const cv::Mat a = TestPattern();
  const auto r = CompareImages(a, a);
  EXPECT_TRUE(std::isinf(r.psnr_db));
  EXPECT_NEAR(r.ssim, 1.0, 1e-6);
  EXPECT_EQ(r.pixels, 64 * 80);
}

TEST(CompareImages, PsnrMatchesItsDefinition) {
  const cv::Mat a = TestPattern();
  cv::Mat b = a.clone();
  // Change every channel of 10% of the pixels by 10: MSE = 0.1 * 100 = 10.
  int changed = 0;
  for (int y = 0; y < b.rows; ++y)
    for (int x = 0; x < b.cols; x += 10, ++changed)
      for (int c = 0; c < 3; ++c) {
        auto& v = b.at<cv::Vec3b>(y, x)[c];
        v = v > 128 ? uchar(v - 10) : uchar(v + 10);
      }
  const double mse = 100.0 * changed / (64.0 * 80.0);
  EXPECT_NEAR(CompareImages(a, b).psnr_db, 10 * std::log10(255.0 * 255.0 / mse), 1e-9);
}

TEST(CompareImages, SsimFallsWithBlurAndMaskSelectsPixels) {
  const cv::Mat a = TestPattern();
  cv::Mat blurred;
  cv::GaussianBlur(a, blurred, {9, 9}, 3);
  const auto r = CompareImages(a, blurred);
  EXPECT_LT(r.ssim, 0.9);
  EXPECT_GT(r.ssim, 0.0);
  cv::Mat b = a.clone();
  b(cv::Rect(0, 0, 40, 64)).setTo(cv::Scalar(0, 0, 0));
  cv::Mat mask(a.size(), CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(40, 0, 40, 64)).setTo(255);
  const auto masked = CompareImages(a, b, mask);
  EXPECT_TRUE(std::isinf(masked.psnr_db));
  EXPECT_EQ(masked.pixels, 40 * 64);
  EXPECT_THROW(CompareImages(a, b(cv::Rect(0, 0, 10, 10)).clone()), Error);
  EXPECT_THROW(CompareImages(a, b, cv::Mat(a.size(), CV_8UC1, cv::Scalar(0))), Error);
}

}  // namespace
}  // namespace lfcam
