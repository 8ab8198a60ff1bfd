#include "lfcam/depth/semi_global.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>

#include "lfcam/core/error.h"

namespace lfcam::semi_global_test {
namespace {

// A volume whose every sample costs 100 except at its own label, which costs 0; where
// `label(x, y)` is negative every label costs the same (no texture).
template <typename Label>
CostVolume Volume(int w, int h, int labels, Label label) {
  CostVolume v;
  v.width = w;
  v.height = h;
  v.labels = labels;
  v.cost.assign(std::size_t(w) * h * labels, 100);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int l = label(x, y);
      std::uint16_t* c = v.at(x, y);
      if (l < 0)
        std::fill(c, c + labels, std::uint16_t(50));
      else
        c[l] = 0;
    }
  return v;
}

int Best(const CostVolume& v, int x, int y) {
  const std::uint16_t* c = v.at(x, y);
  return int(std::min_element(c, c + v.labels) - c);
}

TEST(SemiGlobal, FillsATexturelessRegionFromItsSurroundings) {
  // Label 7 all around; a 20 x 20 hole in the middle where every label costs the same.
  const CostVolume v = Volume(
      60, 50, 16, [](int x, int y) { return x >= 20 && x < 40 && y >= 15 && y < 35 ? -1 : 7; });
  const cv::Mat flat(50, 60, CV_8UC1, cv::Scalar(128));
  const CostVolume s = AggregateSemiGlobal(v, flat, {});
  for (int y = 15; y < 35; y += 3)
    for (int x = 20; x < 40; x += 3) EXPECT_EQ(Best(s, x, y), 7) << x << "," << y;
}

TEST(SemiGlobal, FillsATexturelessBandInASlantAlongTheExpectedSlant) {
  // A surface slanted two labels a sample along x (a jump each sample, to paths expecting no
  // slant), a band 20 samples wide without texture across it: with the slant expected, the paths
  // carry it across the hole; without, they fill it flatter.
  const int w = 40, h = 20;
  const auto slant = [](int x, int) { return 5 + 2 * x; };
  const CostVolume v =
      Volume(w, h, 96, [&](int x, int y) { return x >= 10 && x < 30 ? -1 : slant(x, y); });
  const cv::Mat flat(h, w, CV_8UC1, cv::Scalar(128));
  const cv::Mat expected(h, w, CV_32FC2, cv::Scalar(2.0, 0.0));
  const CostVolume with = AggregateSemiGlobal(v, flat, {}, expected);
  const CostVolume without = AggregateSemiGlobal(v, flat, {});
  int off_without = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 10; x < 30; ++x) {
      EXPECT_EQ(Best(with, x, y), slant(x, y)) << x << "," << y;
      off_without += std::abs(Best(without, x, y) - slant(x, y)) > 1;
    }
  EXPECT_GT(off_without, 200);  // what the expected slant changes: most of the band's 400
  EXPECT_THROW(AggregateSemiGlobal(v, flat, {}, cv::Mat(h, w, CV_32FC1)), Error);
}

TEST(SemiGlobal, KeepsADepthEdgeWhereTheViewHasOneAndAWeakMatchDoesNotWin) {
  // Left half label 3, right half label 12, the guide's edge between them; one sample on the
  // right whose own match says 5 is outvoted by its neighbours.
  CostVolume v = Volume(40, 30, 16, [](int x, int) { return x < 20 ? 3 : 12; });
  std::uint16_t* lone = v.at(30, 15);
  std::fill(lone, lone + 16, std::uint16_t(30));
  lone[5] = 0;
  cv::Mat guide(30, 40, CV_8UC1, cv::Scalar(40));
  guide.colRange(20, 40).setTo(200);
  const CostVolume s = AggregateSemiGlobal(v, guide, {});
  for (int y = 0; y < 30; y += 4) {
    EXPECT_EQ(Best(s, 19, y), 3) << y;
    EXPECT_EQ(Best(s, 20, y), 12) << y;
  }
  EXPECT_EQ(Best(s, 30, 15), 12);
}

TEST(SemiGlobal, RefusesAGuideOfAnotherSize) {
  const CostVolume v = Volume(10, 10, 4, [](int, int) { return 1; });
  EXPECT_THROW(AggregateSemiGlobal(v, cv::Mat(9, 10, CV_8UC1, cv::Scalar(0)), {}), Error);
  EXPECT_THROW(AggregateSemiGlobal(CostVolume{}, cv::Mat(), {}), Error);
}

}  // namespace
}  // namespace lfcam::semi_global_test
