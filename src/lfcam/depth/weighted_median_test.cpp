#include "lfcam/depth/weighted_median.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam::weighted_median_test {
namespace {

// The definition, sample by sample, in double: the median and the two sums that say whether a
// sample is an outlier, with how near to half the nearer of them is (a margin).
struct Definition {
  float median = 0;
  bool outlier = false;
  double margin = 0;  // |sum − half| / total for the sum nearer to deciding
};

Definition Define(const cv::Mat& guide, const cv::Mat& label, int x, int y, int r, double sigma,
                  double threshold) {
  const cv::Vec3b own_colour = guide.at<cv::Vec3b>(y, x);
  const float own = label.at<float>(y, x);
  std::vector<std::pair<float, double>> items;
  double total = 0, below = 0, above = 0;
  for (int yy = std::max(0, y - r); yy <= std::min(label.rows - 1, y + r); ++yy)
    for (int xx = std::max(0, x - r); xx <= std::min(label.cols - 1, x + r); ++xx) {
      const float l = label.at<float>(yy, xx);
      if (std::isnan(l)) continue;
      const cv::Vec3b c = guide.at<cv::Vec3b>(yy, xx);
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += (double(c[k]) - own_colour[k]) * (c[k] - own_colour[k]);
      const double w = std::exp(-d2 / (2 * sigma * sigma));
      items.emplace_back(l, w);
      total += w;
      below += l < own - threshold ? w : 0;
      above += l > own + threshold ? w : 0;
    }
  std::sort(items.begin(), items.end());
  Definition d;
  double cumulative = 0;
  for (const auto& [l, w] : items) {
    cumulative += w;
    if (cumulative >= 0.5 * total) {
      d.median = l;
      break;
    }
  }
  d.outlier = std::abs(d.median - own) > threshold;
  d.margin = std::min(std::abs(below - 0.5 * total), std::abs(above - 0.5 * total)) / total;
  return d;
}

// A guide of smooth colour regions, and labels that follow them with noise and outliers.
std::pair<cv::Mat, cv::Mat> NoisyLabels(int w, int h, unsigned seed) {
  cv::RNG rng(seed);
  cv::Mat guide(h, w, CV_8UC3);
  rng.fill(guide, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(guide, guide, cv::Size(0, 0), 2.5);
  cv::Mat label(h, w, CV_32FC1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const cv::Vec3b c = guide.at<cv::Vec3b>(y, x);
      label.at<float>(y, x) = float(c[0]) / 4.0f + float(rng.gaussian(0.7));
      if (rng.uniform(0.0, 1.0) < 0.08) label.at<float>(y, x) = float(rng.uniform(0.0, 64.0));
      if (rng.uniform(0.0, 1.0) < 0.01)
        label.at<float>(y, x) = std::numeric_limits<float>::quiet_NaN();
    }
  return {guide, label};
}

TEST(WeightedMedian, IsItsDefinitionSampleBySample) {
  for (const int r : {0, 1, 3, 7}) {
    // Widths that are and are not whole numbers of vectors.
    for (const int w : {37, 64}) {
      const auto [guide, label] = NoisyLabels(w, 29, unsigned(7 * r + w));
      const double sigma = 25.5, threshold = 2.0;
      cv::Mat out = label.clone();
      const int replaced = ReplaceOutliersByWeightedMedian(guide, {r, sigma, threshold}, out);
      int expected = 0, disagree = 0;
      for (int y = 0; y < label.rows; ++y)
        for (int x = 0; x < label.cols; ++x) {
          const float own = label.at<float>(y, x), got = out.at<float>(y, x);
          if (std::isnan(own)) {
            EXPECT_TRUE(std::isnan(got)) << x << "," << y;
            continue;
          }
          const Definition d = Define(guide, label, x, y, r, sigma, threshold);
          expected += d.outlier;
          const float want = d.outlier ? d.median : own;
          // Sums in float may decide otherwise only where the definition's are within a hair of
          // half the neighbourhood's weight.
          if (got != want) {
            ++disagree;
            EXPECT_LT(d.margin, 1e-4)
                << "r " << r << " at " << x << "," << y << ": " << got << " against " << want;
          }
        }
      EXPECT_LE(disagree, 2) << "r " << r << " w " << w;
      EXPECT_NEAR(replaced, expected, disagree) << "r " << r << " w " << w;
      if (r > 0) {
        EXPECT_GT(expected, 20) << "the scene must have outliers to find";
      }
    }
  }
}

TEST(WeightedMedian, ReplacesAnIsolatedOutlierAndKeepsAStripOfItsOwnColour) {
  // Two colour halves at labels 10 and 30, one stray sample, and a thin strip of the right
  // half's colour and label reaching into the left half (a thin object in front).
  cv::Mat guide(40, 40, CV_8UC3, cv::Scalar(40, 40, 40));
  guide(cv::Rect(20, 0, 20, 40)).setTo(cv::Scalar(200, 180, 160));
  guide(cv::Rect(5, 10, 12, 2)).setTo(cv::Scalar(200, 180, 160));
  cv::Mat label(40, 40, CV_32FC1, cv::Scalar(10));
  label(cv::Rect(20, 0, 20, 40)).setTo(30);
  label(cv::Rect(5, 10, 12, 2)).setTo(30);
  label.at<float>(30, 8) = 55;  // the stray one
  cv::Mat out = label.clone();
  EXPECT_EQ(ReplaceOutliersByWeightedMedian(guide, {5, 25.5, 2.0}, out), 1);
  EXPECT_EQ(out.at<float>(30, 8), 10.0f);
  EXPECT_EQ(out.at<float>(10, 10), 30.0f);  // the strip stays: its neighbours of its colour agree
  EXPECT_EQ(out.at<float>(20, 19), 10.0f);  // the edge stays where the colours change
  EXPECT_EQ(out.at<float>(20, 20), 30.0f);
  // Without the colour weight (a huge sigma) the strip is outvoted by the half around it.
  cv::Mat plain = label.clone();
  ReplaceOutliersByWeightedMedian(guide, {5, 1e6, 2.0}, plain);
  EXPECT_EQ(plain.at<float>(10, 10), 10.0f);
}

TEST(WeightedMedian, RefusesMapsOfAnotherKind) {
  cv::Mat guide(8, 8, CV_8UC3, cv::Scalar::all(0)), label(8, 9, CV_32FC1, cv::Scalar(1));
  EXPECT_THROW(ReplaceOutliersByWeightedMedian(guide, {}, label), Error);
  cv::Mat ints(8, 8, CV_32SC1, cv::Scalar(1));
  EXPECT_THROW(ReplaceOutliersByWeightedMedian(guide, {}, ints), Error);
  cv::Mat ok(8, 8, CV_32FC1, cv::Scalar(1));
  EXPECT_THROW(ReplaceOutliersByWeightedMedian(guide, {2, 0.0, 2.0}, ok), Error);
}

}  // namespace
}  // namespace lfcam::weighted_median_test
