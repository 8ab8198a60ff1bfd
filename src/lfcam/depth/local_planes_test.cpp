#include "lfcam/depth/local_planes.h"

#include <gtest/gtest.h>
#include <hwy/highway.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/instruction_sets_for_tests.h"

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

// A mask of where refitting may happen (the slant prior's second pass keeps its labels only where
// the first pass was sure): outside it every label stays, inside it each is the unmasked fit's
// own float, though its neighbours outside were not refitted (a fit reads the labels given).
TEST(LocalPlanes, RefitOnlyWhereTheMaskAllows) {
  const int w = 43, h = 31;
  cv::Mat label(h, w, CV_32FC1), confidence(h, w, CV_32FC1), guide(h, w, CV_8UC3);
  cv::Mat only(h, w, CV_8UC1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> scatter(-0.6f, 0.6f), sure(0.0f, 0.2f);
  std::uniform_int_distribution<int> texture(60, 140);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      label.at<float>(y, x) = 12.0f + 0.1f * float(x) - 0.07f * float(y) + scatter(rng);
      confidence.at<float>(y, x) = sure(rng);
      const auto g = std::uint8_t(texture(rng));
      guide.at<cv::Vec3b>(y, x) = {g, std::uint8_t(g / 2), 90};
      only.at<std::uint8_t>(y, x) = (x / 3 + y / 2) % 3 == 0 ? 255 : 0;
    }
  LocalPlaneOptions options;
  options.radius = 10;
  options.sigma_space = 5;
  options.refit_below_confidence = 0.1;
  const cv::Mat everywhere = FitLocalPlanes(label, guide, confidence, options);
  options.refit_only = only;
  const cv::Mat masked = FitLocalPlanes(label, guide, confidence, options);
  int refitted = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool may = only.at<std::uint8_t>(y, x) != 0;
      ASSERT_EQ(masked.at<float>(y, x), may ? everywhere.at<float>(y, x) : label.at<float>(y, x))
          << x << ", " << y;
      refitted += may && masked.at<float>(y, x) != label.at<float>(y, x);
    }
  EXPECT_GT(refitted, w * h / 12);  // half the mask's samples are unsure: about a sixth
  options.refit_only = cv::Mat(h, w + 1, CV_8UC1, cv::Scalar(1));
  EXPECT_THROW(FitLocalPlanes(label, guide, confidence, options), Error);
  options.refit_only = cv::Mat(h, w, CV_32FC1, cv::Scalar(1));
  EXPECT_THROW(FitLocalPlanes(label, guide, confidence, options), Error);
}

// The fit by its definition (local_planes.h), one sample and one neighbour at a time in double:
// what the vectorised fit must give.
cv::Mat ReferenceFit(const cv::Mat& label, const cv::Mat& guide, const cv::Mat& confidence,
                     const LocalPlaneOptions& o, cv::Mat& slopes) {
  const int w = label.cols, h = label.rows, r = o.radius;
  cv::Mat out = label.clone();
  slopes = cv::Mat(label.size(), CV_32FC2, cv::Scalar(0, 0));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!(confidence.at<float>(y, x) < o.refit_below_confidence)) continue;
      const float own = label.at<float>(y, x);
      const cv::Vec3b c0 = guide.at<cv::Vec3b>(y, x);
      cv::Matx33d normal = cv::Matx33d::zeros();
      cv::Vec3d right(0, 0, 0);
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || xx >= w || yy < 0 || yy >= h) continue;
          const double l = label.at<float>(yy, xx) - own;
          if (!(std::abs(l) <= o.max_label_gap)) continue;
          const cv::Vec3b c = guide.at<cv::Vec3b>(yy, xx);
          double d2 = 0;
          for (int k = 0; k < 3; ++k) d2 += (double(c[k]) - c0[k]) * (double(c[k]) - c0[k]);
          const double s = o.sigma_colour * 255;
          const double weight =
              std::exp(-(dx * dx + dy * dy) / (2 * o.sigma_space * o.sigma_space)) *
              std::exp(-d2 / (2 * s * s)) *
              std::max(double(confidence.at<float>(yy, xx)), o.min_confidence);
          const cv::Vec3d term(1, dx, dy);
          normal += weight * term * term.t();
          right += weight * l * term;
        }
      if (normal(0, 0) <= 0) continue;
      normal(1, 1) += 1e-3 * normal(0, 0);
      normal(2, 2) += 1e-3 * normal(0, 0);
      const cv::Vec3d plane = normal.solve(right, cv::DECOMP_LU);
      out.at<float>(y, x) = own + float(plane[0]);
      slopes.at<cv::Vec2f>(y, x) = {float(plane[1]), float(plane[2])};
    }
  return out;
}

// Random maps with edges in colour and depth, every instruction set Highway compiled in that this
// machine runs, both of the estimate's fits (radius 5 over every sample, radius 10 over the
// unconfident ones), on a width that is no whole number of vectors.
TEST(LocalPlanes, TheVectorisedFitIsTheDefinitionsOnEveryInstructionSet) {
  const int w = 53, h = 31;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0, 1);
  cv::Mat label(h, w, CV_32FC1), confidence(h, w, CV_32FC1), guide(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool near = x > 20 + y / 3;
      label.at<float>(y, x) = (near ? 30.0f : 12.0f + 0.1f * float(x)) + 2.0f * unit(rng);
      confidence.at<float>(y, x) = unit(rng) * unit(rng);
      const int base = near ? 180 : 60;
      guide.at<cv::Vec3b>(y, x) = {std::uint8_t(base + 40 * unit(rng)),
                                   std::uint8_t(base + 40 * unit(rng)), std::uint8_t(90)};
    }
  LocalPlaneOptions narrow;
  narrow.max_label_gap = 3;
  LocalPlaneOptions wide = narrow;
  wide.radius = 10;
  wide.sigma_space = 5;
  wide.refit_below_confidence = 0.1;
  const std::vector<std::int64_t> targets = testing::InstructionSetsThisMachineRuns();
  ASSERT_FALSE(targets.empty());
  double worst = 0, worst_slope = 0;
  for (const LocalPlaneOptions& o : {narrow, wide}) {
    cv::Mat reference_slopes;
    const cv::Mat reference = ReferenceFit(label, guide, confidence, o, reference_slopes);
    ASSERT_GT(cv::norm(reference, label, cv::NORM_INF), 0.5);  // the fit moves labels
    for (const std::int64_t target : targets) {
      hwy::SetSupportedTargetsForTest(target);
      cv::Mat slopes;
      const cv::Mat fitted = FitLocalPlanes(label, guide, confidence, o, &slopes);
      const double difference = cv::norm(fitted, reference, cv::NORM_INF);
      const double slope_difference = cv::norm(slopes, reference_slopes, cv::NORM_INF);
      EXPECT_LT(difference, 1e-3) << hwy::TargetName(target) << ", radius " << o.radius;
      EXPECT_LT(slope_difference, 1e-3) << hwy::TargetName(target) << ", radius " << o.radius;
      worst = std::max(worst, difference);
      worst_slope = std::max(worst_slope, slope_difference);
    }
    hwy::SetSupportedTargetsForTest(0);
  }
  std::cout << "largest difference from the definition: " << worst << " labels, " << worst_slope
            << " labels a sample in slope\n";
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
