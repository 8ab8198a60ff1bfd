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

WeightedMedianOptions Options(int radius, double sigma_levels, double threshold) {
  WeightedMedianOptions options;
  options.radius = radius;
  options.sigma_levels = sigma_levels;
  options.threshold = threshold;
  return options;
}

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

// Every sample of `label` cleaned up at radius r against the definition; returns how many the
// definition replaces.
int ExpectTheDefinition(const cv::Mat& guide, const cv::Mat& label, int r) {
  const double sigma = 25.5, threshold = 2.0;
  cv::Mat out = label.clone();
  const int replaced = ReplaceOutliersByWeightedMedian(guide, Options(r, sigma, threshold), out);
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
        EXPECT_LT(d.margin, 1e-4) << "r " << r << " at " << x << "," << y << ": " << got
                                  << " against " << want;
      }
    }
  EXPECT_LE(disagree, 2) << "r " << r << " w " << label.cols;
  EXPECT_NEAR(replaced, expected, disagree) << "r " << r << " w " << label.cols;
  return expected;
}

TEST(WeightedMedian, IsItsDefinitionSampleBySample) {
  for (const int r : {0, 1, 3, 7}) {
    // Widths that are and are not whole numbers of vectors.
    for (const int w : {37, 64}) {
      const auto [guide, label] = NoisyLabels(w, 29, unsigned(7 * r + w));
      const int expected = ExpectTheDefinition(guide, label, r);
      if (r > 0) {
        EXPECT_GT(expected, 20) << "the scene must have outliers to find";
      }
    }
  }
}

// The median is looked for among the labels cut into buckets in their order: whole labels (many
// ties within a bucket), one label far beyond the rest (all the others in one bucket), or every
// label the same, it is still the definition's.
TEST(WeightedMedian, IsItsDefinitionWhateverTheLabelsSpread) {
  for (const int kind : {0, 1, 2}) {
    auto [guide, label] = NoisyLabels(48, 31, unsigned(101 + kind));
    for (int y = 0; y < label.rows; ++y)
      for (int x = 0; x < label.cols; ++x) {
        float& l = label.at<float>(y, x);
        if (std::isnan(l)) continue;
        if (kind == 0) l = std::round(l);
        if (kind == 2) l = 5.0f;
      }
    if (kind == 1) label.at<float>(3, 4) = 1.0e6f;
    const int expected = ExpectTheDefinition(guide, label, 5);
    if (kind != 2) {
      EXPECT_GT(expected, 20) << "the scene must have outliers to find";
    }
  }
}

// With a mask, a sample the mask allows takes what the unmasked clean-up gives it, and every other
// keeps its label while still counting in its neighbours' medians (the mask decides what is
// replaced, not what votes).
TEST(WeightedMedian, ReplacesOnlyWhereTheMaskAllows) {
  const auto [guide, label] = NoisyLabels(64, 29, 11u);
  cv::Mat everywhere = label.clone();
  const int all = ReplaceOutliersByWeightedMedian(guide, Options(3, 25.5, 2.0), everywhere);
  ASSERT_GT(all, 20) << "the scene must have outliers to find";
  WeightedMedianOptions masked = Options(3, 25.5, 2.0);
  masked.replace_only = cv::Mat(label.size(), CV_8UC1, cv::Scalar(0));
  masked.replace_only(cv::Rect(0, 0, 32, 29)).setTo(1);  // the left half
  cv::Mat some = label.clone();
  const int replaced = ReplaceOutliersByWeightedMedian(guide, masked, some);
  EXPECT_GT(replaced, 0);
  EXPECT_LT(replaced, all);
  for (int y = 0; y < label.rows; ++y)
    for (int x = 0; x < label.cols; ++x) {
      const float want = x < 32 ? everywhere.at<float>(y, x) : label.at<float>(y, x);
      const float got = some.at<float>(y, x);
      EXPECT_TRUE(got == want || (std::isnan(got) && std::isnan(want))) << x << "," << y;
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
  EXPECT_EQ(ReplaceOutliersByWeightedMedian(guide, Options(5, 25.5, 2.0), out), 1);
  EXPECT_EQ(out.at<float>(30, 8), 10.0f);
  EXPECT_EQ(out.at<float>(10, 10), 30.0f);  // the strip stays: its neighbours of its colour agree
  EXPECT_EQ(out.at<float>(20, 19), 10.0f);  // the edge stays where the colours change
  EXPECT_EQ(out.at<float>(20, 20), 30.0f);
  // Without the colour weight (a huge sigma) the strip is outvoted by the half around it.
  cv::Mat plain = label.clone();
  ReplaceOutliersByWeightedMedian(guide, Options(5, 1e6, 2.0), plain);
  EXPECT_EQ(plain.at<float>(10, 10), 10.0f);
}

TEST(WeightedMedian, KeepsADarkLimbOnItsObjectAndMovesTheFattenedBackground) {
  // A wall (grey 80, label 30: far) left of an object (grey 140, label 10: near). Between them,
  // the object's limb (column 21, grey 67: darker than both) and a column of wall the sweep
  // fattened onto the object (column 20, the wall's grey), both at the object's label.
  cv::Mat guide(40, 40, CV_8UC3, cv::Scalar::all(80));
  guide(cv::Rect(22, 0, 18, 40)).setTo(cv::Scalar::all(140));
  guide(cv::Rect(21, 0, 1, 40)).setTo(cv::Scalar::all(67));
  guide.at<cv::Vec3b>(30, 18) = cv::Vec3b(60, 60, 60);  // one sample of the wall as dark
  cv::Mat label(40, 40, CV_32FC1, cv::Scalar(30));
  label(cv::Rect(20, 0, 20, 40)).setTo(10);
  // The median moves both onto the wall: the limb is more like the wall than like the object.
  cv::Mat plain = label.clone();
  ReplaceOutliersByWeightedMedian(guide, Options(7, 25.5, 2.0), plain);
  EXPECT_EQ(plain.at<float>(10, 20), 30.0f);
  EXPECT_EQ(plain.at<float>(10, 21), 30.0f);
  EXPECT_EQ(plain.at<float>(10, 22), 10.0f);
  // Kept as a limb where it lies 4 levels below the wall around it and its object's mean; the
  // fattened wall still moves, and so does the limb where the wall is as dark within 3 samples.
  WeightedMedianOptions limbs = Options(7, 25.5, 2.0);
  limbs.dark_limb_levels = 4;
  cv::Mat kept = label.clone();
  ReplaceOutliersByWeightedMedian(guide, limbs, kept);
  EXPECT_EQ(kept.at<float>(10, 20), 30.0f);
  EXPECT_EQ(kept.at<float>(10, 21), 10.0f);
  EXPECT_EQ(kept.at<float>(26, 21), 10.0f);
  for (const int y : {27, 30, 33}) EXPECT_EQ(kept.at<float>(y, 21), 30.0f) << y;
  // Not kept where it is less than the levels asked below the wall (80 - 67 = 13).
  limbs.dark_limb_levels = 14;
  cv::Mat strict = label.clone();
  ReplaceOutliersByWeightedMedian(guide, limbs, strict);
  EXPECT_EQ(strict.at<float>(10, 21), 30.0f);
  // A sample the median leaves nearer is never kept by this rule: the object's far side is not a
  // limb (the same map read with near and far exchanged moves the strip onto the object).
  cv::Mat reversed = 40.0f - label;
  limbs.dark_limb_levels = 4;
  ReplaceOutliersByWeightedMedian(guide, limbs, reversed);
  EXPECT_EQ(reversed.at<float>(10, 21), 10.0f);
}

TEST(WeightedMedian, RefusesMapsOfAnotherKind) {
  cv::Mat guide(8, 8, CV_8UC3, cv::Scalar::all(0)), label(8, 9, CV_32FC1, cv::Scalar(1));
  EXPECT_THROW(ReplaceOutliersByWeightedMedian(guide, {}, label), Error);
  cv::Mat ints(8, 8, CV_32SC1, cv::Scalar(1));
  EXPECT_THROW(ReplaceOutliersByWeightedMedian(guide, {}, ints), Error);
  cv::Mat ok(8, 8, CV_32FC1, cv::Scalar(1));
  EXPECT_THROW(ReplaceOutliersByWeightedMedian(guide, Options(2, 0.0, 2.0), ok), Error);
  WeightedMedianOptions negative;
  negative.dark_limb_levels = -1;
  EXPECT_THROW(ReplaceOutliersByWeightedMedian(guide, negative, ok), Error);
  WeightedMedianOptions masked;
  masked.replace_only = cv::Mat(8, 8, CV_32FC1, cv::Scalar(1));  // not an 8-bit map
  EXPECT_THROW(ReplaceOutliersByWeightedMedian(guide, masked, ok), Error);
  masked.replace_only = cv::Mat(8, 9, CV_8UC1, cv::Scalar(1));  // not the labels' size
  EXPECT_THROW(ReplaceOutliersByWeightedMedian(guide, masked, ok), Error);
}

}  // namespace
}  // namespace lfcam::weighted_median_test
