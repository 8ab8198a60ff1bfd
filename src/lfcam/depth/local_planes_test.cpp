#include "lfcam/depth/local_planes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <random>

#include "lfcam/core/error.h"

namespace lfcam::local_planes_test {
namespace {

// A slanted surface whose labels were chosen a whole plane at a time (the staircase a sweep
// leaves) and scattered by a plane here and there: the fitted planes follow the slant.
TEST(LocalPlanes, FollowASlantedSurfaceThroughItsStaircase) {
  const int w = 96, h = 80;
  const auto truth = [](int x, int y) { return 20.0 + 0.13 * x + 0.31 * y; };
  cv::Mat label(h, w, CV_32FC1), confidence(h, w, CV_32FC1, cv::Scalar(1.0f));
  cv::Mat guide(h, w, CV_8UC3);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> texture(90, 110), scatter(-1, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      label.at<float>(y, x) = float(std::round(truth(x, y)) + (rng() % 5 == 0 ? scatter(rng) : 0));
      const auto g = std::uint8_t(texture(rng));
      guide.at<cv::Vec3b>(y, x) = {g, g, g};
    }
  const cv::Mat fitted = FitLocalPlanes(label, guide, confidence);
  double before = 0, after = 0;
  int n = 0;
  for (int y = 6; y < h - 6; ++y)
    for (int x = 6; x < w - 6; ++x, ++n) {
      before += std::pow(label.at<float>(y, x) - truth(x, y), 2);
      after += std::pow(fitted.at<float>(y, x) - truth(x, y), 2);
    }
  const double rms_before = std::sqrt(before / n), rms_after = std::sqrt(after / n);
  EXPECT_GT(rms_before, 0.35);
  EXPECT_LT(rms_after, 0.12) << "the staircase's RMS error was " << rms_before;
}

// Two surfaces meeting at an edge that is both a colour edge and a depth edge: each side keeps
// its own labels (neither the far side's colour nor its depth counts).
TEST(LocalPlanes, KeepADepthEdgeWhereTheColourChanges) {
  const int w = 40, h = 30;
  cv::Mat label(h, w, CV_32FC1), confidence(h, w, CV_32FC1, cv::Scalar(0.8f));
  cv::Mat guide(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool near = x >= 17;
      label.at<float>(y, x) = near ? 40.0f : 10.0f + 0.05f * float(x);
      guide.at<cv::Vec3b>(y, x) = near ? cv::Vec3b{200, 60, 40} : cv::Vec3b{40, 90, 200};
    }
  const cv::Mat fitted = FitLocalPlanes(label, guide, confidence);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      ASSERT_NEAR(fitted.at<float>(y, x), label.at<float>(y, x), 1e-3) << x << ", " << y;
}

// A neighbour across a depth gap wider than max_label_gap does not count even where the colour
// is the same (a surface in front of another of its colour).
TEST(LocalPlanes, LeaveOutNeighboursAcrossADepthGapOfTheSameColour) {
  const int w = 30, h = 20;
  cv::Mat label(h, w, CV_32FC1), confidence(h, w, CV_32FC1, cv::Scalar(1.0f));
  cv::Mat guide(h, w, CV_8UC3, cv::Scalar(120, 120, 120));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) label.at<float>(y, x) = x < 15 ? 5.0f : 30.0f;
  LocalPlaneOptions options;
  options.max_label_gap = 10;
  const cv::Mat fitted = FitLocalPlanes(label, guide, confidence, options);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      ASSERT_NEAR(fitted.at<float>(y, x), label.at<float>(y, x), 1e-3) << x << ", " << y;
}

// refit_below_confidence: the confident samples keep their labels exactly, the others are
// refitted (here onto the slant their neighbours agree on).
TEST(LocalPlanes, RefitOnlyTheSamplesLessConfidentThanAsked) {
  const int w = 40, h = 30;
  cv::Mat label(h, w, CV_32FC1), confidence(h, w, CV_32FC1);
  const cv::Mat guide(h, w, CV_8UC3, cv::Scalar(100, 100, 100));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool odd = (x + y) % 2 == 1;
      label.at<float>(y, x) = 10.0f + 0.2f * float(x) + (odd ? 0.5f : 0.0f);
      confidence.at<float>(y, x) = odd ? 0.02f : 0.6f;
    }
  LocalPlaneOptions options;
  options.refit_below_confidence = 0.1;
  const cv::Mat fitted = FitLocalPlanes(label, guide, confidence, options);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if ((x + y) % 2 == 0)
        ASSERT_EQ(fitted.at<float>(y, x), label.at<float>(y, x)) << x << ", " << y;
      else  // pulled from +0.5 off the slant towards its confident neighbours' plane
        ASSERT_LT(std::abs(fitted.at<float>(y, x) - (10.0f + 0.2f * float(x))), 0.2f)
            << x << ", " << y;
    }
}

TEST(LocalPlanes, RefuseMapsOfAnotherTypeOrSize) {
  const cv::Mat label(8, 8, CV_32FC1, cv::Scalar(1.0f)), guide(8, 8, CV_8UC3);
  const cv::Mat confidence(8, 8, CV_32FC1, cv::Scalar(1.0f));
  EXPECT_THROW(FitLocalPlanes(cv::Mat(8, 9, CV_32FC1), guide, confidence), Error);
  EXPECT_THROW(FitLocalPlanes(label, cv::Mat(8, 8, CV_8UC1), confidence), Error);
  EXPECT_THROW(FitLocalPlanes(label, guide, cv::Mat(8, 8, CV_64FC1)), Error);
  EXPECT_NO_THROW(FitLocalPlanes(label, guide, confidence));
}

}  // namespace
}  // namespace lfcam::local_planes_test
