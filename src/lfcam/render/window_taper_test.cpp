#include "lfcam/render/window_taper.h"

#include <gtest/gtest.h>

namespace lfcam {
namespace {

// The share against the tent integrated numerically over the window.
double Integrated(double x, double lo, double hi, double h) {
  constexpr int kSteps = 200000;
  double inside = 0, total = 0;
  for (int n = 0; n < kSteps; ++n) {
    const double y = x - h + (n + 0.5) * 2 * h / kSteps;
    const double tent = 1.0 - std::abs(y - x) / h;
    total += tent;
    if (y >= lo && y <= hi) inside += tent;
  }
  return inside / total;
}

TEST(WindowTaper, ACameraCountsByTheShareOfItsTentInsideTheWindow) {
  // No tent: the hard edge, both ends included.
  EXPECT_EQ(TentShareInside(-0.5, -0.5, 9.5, 0), 1.0);
  EXPECT_EQ(TentShareInside(9.5, -0.5, 9.5, 0), 1.0);
  EXPECT_EQ(TentShareInside(9.5001, -0.5, 9.5, 0), 0.0);
  EXPECT_EQ(TentShareInside(-0.5001, -0.5, 9.5, 0), 0.0);
  for (const double h : {0.4, 2.0, 7.5}) {
    SCOPED_TRACE(h);
    // Half the tent at an edge, all of it a half-width inside, none a half-width outside.
    EXPECT_NEAR(TentShareInside(-0.5, -0.5, 40.5, h), 0.5, 1e-12);
    EXPECT_NEAR(TentShareInside(40.5, -0.5, 40.5, h), 0.5, 1e-12);
    EXPECT_EQ(TentShareInside(-0.5 + h, -0.5, 40.5, h), 1.0);
    EXPECT_EQ(TentShareInside(-0.5 - h, -0.5, 40.5, h), 0.0);
    for (const double x : {-0.5 - 0.7 * h, -0.5 - 0.2 * h, -0.5 + 0.3 * h, 40.5 - 0.9 * h}) {
      EXPECT_NEAR(TentShareInside(x, -0.5, 40.5, h), Integrated(x, -0.5, 40.5, h), 2e-5) << x;
      // Mirrored about the window's centre, the same share.
      EXPECT_NEAR(TentShareInside(x, -0.5, 40.5, h), TentShareInside(40.0 - x, -0.5, 40.5, h),
                  1e-12);
    }
    // A window narrower than the tent holds only its part.
    EXPECT_NEAR(TentShareInside(0.3, -0.5, 0.5, h), Integrated(0.3, -0.5, 0.5, h), 2e-5);
  }
  // Along both axes at once: the product.
  WindowTaper taper;
  taper.h_k = 2;
  taper.h_l = 0.5;
  taper.windows = {{-0.5f, -0.5f, 9.5f, 4.5f}};
  EXPECT_NEAR(taper.Share(0, -0.5, 4.5), 0.25, 1e-7);
  EXPECT_NEAR(taper.Share(0, 4, 2), 1.0, 1e-12);
  EXPECT_EQ(taper.Share(0, 4, 5.0), 0.0);
}

}  // namespace
}  // namespace lfcam
