#include "lfcam/render/aperture_weights.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace lfcam {
namespace {

// The renderer's clamped bilinear weight of camera i along one axis of n (the lookup's rule).
double LookupWeight(double x, int i, int n) {
  if (x < -0.5 || x > n - 0.5) return 0.0;
  const double xc = std::clamp(x, 0.0, double(n - 1));
  if (n == 1) return 1.0;
  const int i0 = std::min(int(xc), n - 2);
  const double w1 = xc - i0;
  return i == i0 ? 1.0 - w1 : i == i0 + 1 ? w1 : 0.0;
}

// The integral by brute force: a fine midpoint grid over the disk's bounding square.
double BruteForce(double radius, double cx, double cy, int col, int row, int cols, int rows) {
  const int n = 1200;
  const double step = 2.0 * radius / n;
  double sum = 0.0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const double x = cx - radius + (a + 0.5) * step, y = cy - radius + (b + 0.5) * step;
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > radius * radius) continue;
      sum += LookupWeight(x, col, cols) * LookupWeight(y, row, rows);
    }
  return sum * step * step;
}

TEST(ApertureWeights, IntegralsMatchBruteForceInsideAndAtTheWindowsEdges) {
  struct Case {
    double radius, cx, cy;
    int col, row;
  };
  for (const Case& c :
       {Case{0.7, 4.3, 5.6, 4, 5}, Case{2.3, 4.5, 4.5, 3, 6}, Case{4.6, 5.2, 3.9, 7, 2},
        Case{1.5, 0.2, 8.7, 0, 9}, Case{3.0, -0.8, 4.4, 0, 4}, Case{0.3, 9.3, 0.1, 9, 0}}) {
    SCOPED_TRACE(::testing::Message() << c.radius << " " << c.cx << " " << c.cy);
    const double exact = DiskCameraIntegral(c.radius, c.cx, c.cy, c.col, c.row, 10, 10);
    const double brute = BruteForce(c.radius, c.cx, c.cy, c.col, c.row, 10, 10);
    EXPECT_GT(exact, 0.0);
    // The brute force's own error: its grid's cells cut by the circle and the kinks.
    EXPECT_NEAR(exact, brute, 2e-3 * std::max(brute, 0.05 * c.radius * c.radius));
  }
}

TEST(ApertureWeights, WeightsArePositiveSumToOneAndShrinkToBilinear) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> position(-0.4, 9.4), size(0.05, 6.0);
  for (int trial = 0; trial < 40; ++trial) {
    const double cx = position(rng), cy = position(rng), radius = size(rng);
    const auto w = DiskCameraWeights(radius, cx, cy, 10, 10);
    ASSERT_FALSE(w.empty());
    double total = 0.0;
    for (const auto& c : w) {
      EXPECT_GT(c.weight, 0.0);
      total += c.weight;
    }
    EXPECT_NEAR(total, 1.0, 1e-12);
  }
  // A tiny disk: the bilinear weights of its centre.
  for (const double radius : {0.0, 1e-4}) {
    const auto w = DiskCameraWeights(radius, 3.25, 6.5, 10, 10);
    ASSERT_EQ(w.size(), 4u);
    for (const auto& c : w)
      EXPECT_NEAR(c.weight, LookupWeight(3.25, c.col, 10) * LookupWeight(6.5, c.row, 10), 1e-3);
  }
  // Symmetry: a disk centred on a camera weighs its four neighbours alike.
  const auto w = DiskCameraWeights(1.7, 5.0, 5.0, 10, 10);
  auto at = [&](int col, int row) {
    for (const auto& c : w)
      if (c.col == col && c.row == row) return c.weight;
    return 0.0;
  };
  EXPECT_NEAR(at(4, 5), at(6, 5), 1e-12);
  EXPECT_NEAR(at(4, 5), at(5, 4), 1e-12);
  EXPECT_GT(at(5, 5), at(4, 5));
  // Outside the window: nothing.
  EXPECT_TRUE(DiskCameraWeights(0.5, -2.0, 4.0, 10, 10).empty());
}

// The weights come from one sweep of the disk for all cameras: each must be its own camera's
// integral (DiskCameraIntegral, checked against brute force above), normalised, on grids of one
// camera a side up to the reference design's, the window's edges and corners included.
TEST(ApertureWeights, EachWeightIsItsCamerasOwnIntegral) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0;
  for (const auto& [cols, rows] : {std::pair{10, 10}, {1, 1}, {1, 7}, {17, 3}, {2, 2}}) {
    for (int trial = 0; trial < 60; ++trial) {
      const double cx = -1.0 + (cols + 1.0) * unit(rng), cy = -1.0 + (rows + 1.0) * unit(rng);
      const double radius = trial % 10 == 0 ? 1e-3 : 0.05 + 6.0 * unit(rng) * unit(rng);
      SCOPED_TRACE(::testing::Message()
                   << cols << "x" << rows << " disk " << radius << " at " << cx << ", " << cy);
      std::vector<double> own(std::size_t(cols) * rows);
      double total = 0.0;
      for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
          total += own[std::size_t(r) * cols + c] =
              DiskCameraIntegral(radius, cx, cy, c, r, cols, rows);
      const auto weights = DiskCameraWeights(radius, cx, cy, cols, rows);
      if (!(total > 1e-15)) {
        EXPECT_TRUE(weights.empty());
        continue;
      }
      std::vector<double> swept(own.size(), 0.0);
      for (const GridCameraWeight& w : weights) swept[std::size_t(w.row) * cols + w.col] = w.weight;
      for (std::size_t i = 0; i < own.size(); ++i) {
        EXPECT_NEAR(swept[i], own[i] / total, 1e-9) << "camera " << i;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 5000);
}

}  // namespace
}  // namespace lfcam
