#include "lfcam/sim/board_radiance.h"

#include <gtest/gtest.h>

#include <random>

namespace lfcam {
namespace {

double BruteForceBlack(const BoardSpec& b, double x0, double x1, double y0, double y1) {
  const int n = 400;
  int black = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = x0 + (i + 0.5) / n * (x1 - x0), y = y0 + (j + 0.5) / n * (y1 - y0);
      const bool inside = x >= 0 && y >= 0 && x < b.width_mm() && y < b.height_mm();
      black += inside && b.black_at(x, y);
    }
  return double(black) / (n * n);
}

TEST(BoardRadiance, BlackAreaIsTheExactShareUnderTheFootprint) {
  const BoardSpec b{10, 7, 30.0};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-40, 360), size(0.5, 70);
  for (int trial = 0; trial < 40; ++trial) {
    const double x0 = pos(rng), y0 = pos(rng) * 0.7, w = size(rng), h = size(rng);
    EXPECT_NEAR(BlackAreaFraction(b, x0, x0 + w, y0, y0 + h),
                BruteForceBlack(b, x0, x0 + w, y0, y0 + h), 4e-3)
        << x0 << " " << y0 << " " << w << " " << h;
  }
  // Straddling a corner symmetrically: half black.
  EXPECT_NEAR(BlackAreaFraction(b, 25, 35, 25, 35), 0.5, 1e-12);
  // Inside one square.
  EXPECT_NEAR(BlackAreaFraction(b, 1, 2, 1, 2), 1.0, 1e-12);
  EXPECT_NEAR(BlackAreaFraction(b, 31, 32, 1, 2), 0.0, 1e-12);
  // Outside the squared area: the white margin.
  EXPECT_NEAR(BlackAreaFraction(b, -20, -10, 5, 10), 0.0, 1e-12);
}

}  // namespace
}  // namespace lfcam
