#include "lfcam/render/lens_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace lfcam {
namespace {

TEST(ConcentricDisk, MapsIntoTheDiskAndCoversIt) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uniform(0, 1);
  double max_r = 0;
  for (int n = 0; n < 100000; ++n) {
    const Vec2 p = SampleUniformDiskConcentric({uniform(rng), uniform(rng)});
    EXPECT_LE(p.norm(), 1 + 1e-12);
    max_r = std::max(max_r, p.norm());
  }
  EXPECT_GT(max_r, 0.999);
  EXPECT_TRUE(SampleUniformDiskConcentric({0.5, 0.5}).isZero());
  EXPECT_NEAR(SampleUniformDiskConcentric({1.0, 0.5}).x(), 1.0, 1e-12);
}

TEST(ConcentricDisk, DensityIsUniform) {
  // Equal-area bins: 4 rings of equal area x 8 sectors, each should get 1/32 of the samples.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0, 1);
  constexpr int kSamples = 320000;
  int bins[4][8] = {};
  for (int n = 0; n < kSamples; ++n) {
    const Vec2 p = SampleUniformDiskConcentric({uniform(rng), uniform(rng)});
    const int ring = std::min(3, int(p.squaredNorm() * 4));
    const double angle = std::atan2(p.y(), p.x()) + std::numbers::pi;
    const int sector = std::min(7, int(angle / (2 * std::numbers::pi) * 8));
    ++bins[ring][sector];
  }
  const double expected = kSamples / 32.0;
  for (auto& ring : bins)
    for (int count : ring) EXPECT_NEAR(count, expected, 5 * std::sqrt(expected));
}

TEST(LensSampleCount, IsThePapersFormula) {
  // n_ls = gamma (d_l / 2)^2 / 210.
  EXPECT_EQ(LensSampleCount(1, 64), 5);      // 4.88
  EXPECT_EQ(LensSampleCount(4, 192), 176);   // 175.5 rounds up
  EXPECT_EQ(LensSampleCount(9, 256), 702);   // 702.17
  EXPECT_EQ(LensSampleCount(16, 128), 312);  // 312.08
  EXPECT_EQ(LensSampleCount(1, 1), 1);       // never zero
}

TEST(UnitDiskSamples, AreInsideTheDiskAndCentred) {
  for (int n : {1, 5, 176, 1248}) {
    const auto samples = UnitDiskSamples(n);
    ASSERT_EQ(int(samples.size()), n);
    Vec2 mean = Vec2::Zero();
    for (const Vec2& s : samples) {
      EXPECT_LE(s.norm(), 1 + 1e-12);
      mean += s / n;
    }
    EXPECT_LT(mean.norm(), n == 1 ? 1e-12 : 0.5 / n + 0.02) << n;
  }
}

}  // namespace
}  // namespace lfcam
