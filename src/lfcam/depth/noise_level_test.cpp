#include "lfcam/depth/noise_level.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace lfcam {
namespace {

// A photograph-like image: smooth shading, fine texture and hard-edged shapes, 8-bit RGB.
cv::Mat TexturedImage() {
  cv::RNG rng(7);
  cv::Mat texture(240, 320, CV_32FC3);
  rng.fill(texture, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 1.2);
  cv::Mat image(240, 320, CV_32FC3);
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) {
      const float shade = 40.0f + 0.4f * float(x) + 0.2f * float(y);
      const cv::Vec3f t = texture.at<cv::Vec3f>(y, x);
      image.at<cv::Vec3f>(y, x) =
          cv::Vec3f(shade, shade, shade) + 0.6f * (t - cv::Vec3f(128, 128, 128));
    }
  cv::rectangle(image, {40, 30, 90, 70}, cv::Scalar(230, 40, 40), cv::FILLED);
  cv::circle(image, {220, 150}, 50, cv::Scalar(20, 200, 90), cv::FILLED);
  return image;
}

cv::Mat WithNoise(const cv::Mat& image, double sigma) {
  cv::Mat noise(image.size(), image.type());
  cv::RNG rng(11);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  cv::Mat out;
  cv::Mat(image + noise).convertTo(out, CV_8UC3);
  return out;
}

TEST(NoiseLevel, MeasuresTheNoiseAndNotTheTexture) {
  const cv::Mat image = TexturedImage();
  // Clean: the texture (a fifth of a level's quantisation aside) does not count.
  EXPECT_LT(NoiseLevel(WithNoise(image, 0.0)), 1.0);
  for (const double sigma : {1.5, 3.0, 6.0}) {
    const double measured = NoiseLevel(WithNoise(image, sigma));
    EXPECT_NEAR(measured, sigma, 0.2 * sigma) << sigma;
  }
  // Every share of the flattest samples: more texture counts as the share grows.
  EXPECT_LE(NoiseLevel(WithNoise(image, 0.0), 0.1), NoiseLevel(WithNoise(image, 0.0), 1.0));
}

TEST(NoiseLevel, SaysZeroForAnImageTooSmallAndRefusesOtherDepths) {
  EXPECT_EQ(NoiseLevel(cv::Mat(2, 2, CV_8UC3, cv::Scalar::all(9))), 0.0);
  EXPECT_ANY_THROW(NoiseLevel(cv::Mat(8, 8, CV_32FC3, cv::Scalar::all(9))));
}

}  // namespace
}  // namespace lfcam
