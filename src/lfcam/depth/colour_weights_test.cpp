#include "lfcam/depth/colour_weights.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>

#include "lfcam/core/error.h"

namespace lfcam::colour_weights_test {
namespace {

constexpr int kLargestSquaredDistance = 3 * 255 * 255;

// At the clean-up's scales (the plane fit's σ of 0.06 · 255 levels, the weighted median's 25.5)
// and a narrow and a wide one: every entry the exponential of its distance, to a float's
// precision; the table ends where the exponential has reached 0, or holds every distance.
TEST(ColourWeights, AreTheExponentialOfEverySquaredDistanceAndEndWhereTheyReachZero) {
  for (const double sigma : {0.06 * 255, 25.5, 2.0, 400.0}) {
    SCOPED_TRACE(sigma);
    const float scale = float(-1.0 / (2 * sigma * sigma));
    const ColourWeights table = MakeColourWeights(scale);
    ASSERT_EQ(table.weight.size(), std::size_t(table.last) + 1);
    ASSERT_LE(table.last, kLargestSquaredDistance);
    EXPECT_EQ(table.weight[0], 1.0f);
    for (int n = 0; n <= table.last; ++n) {
      const double truth = std::exp(double(n) * double(scale));
      const float w = table.weight[std::size_t(n)];
      if (truth > 1e-30) {
        // The float product n · scale is rounded: its relative error, times |n · scale|, is
        // the exponential's.
        ASSERT_NEAR(w, truth, 1.5e-7 * (2 + std::abs(double(n) * scale)) * truth) << n;
      } else {
        ASSERT_LE(w, 1e-29) << n;
      }
      if (n > 0) {
        ASSERT_LE(w, table.weight[std::size_t(n - 1)]) << n;
      }
    }
    if (table.last < kLargestSquaredDistance) {
      // Every distance past the table weighs what its last entry does: nothing.
      EXPECT_EQ(table.weight.back(), 0.0f);
      EXPECT_LT(std::exp(double(table.last) * double(scale)),
                1e3 * double(std::numeric_limits<float>::min()));
    } else {
      EXPECT_GT(table.weight.back(), 0.0f);
    }
  }
  EXPECT_LT(MakeColourWeights(float(-1.0 / (2 * 2.0 * 2.0))).last, 10000);
  EXPECT_EQ(MakeColourWeights(float(-1.0 / (2 * 400.0 * 400.0))).last, kLargestSquaredDistance);
  EXPECT_THROW(MakeColourWeights(0.0f), Error);
  EXPECT_THROW(MakeColourWeights(std::numeric_limits<float>::quiet_NaN()), Error);
}

}  // namespace
}  // namespace lfcam::colour_weights_test
