#include "lfcam/core/slab.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"

namespace lfcam {
namespace {

Slab PaperLikeSlab() {
  Slab slab;
  slab.uv.p_ca = Vec3(160, 135, 3600);
  slab.st = ViewWindow{Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 600, 550};
  return slab;
}

TEST(Slab, CameraCentresFollowThePapersConvention) {
  const Slab slab = PaperLikeSlab();
  // (u_i, v_j) = ((i + 0.5) / 10, (j + 0.5) / 10), 28 mm apart, (0, 0) bottom left.
  EXPECT_TRUE(slab.uv.camera_center(0, 0).isApprox(Vec3(174, 149, 3600)));
  EXPECT_TRUE(slab.uv.camera_center(0, 9).isApprox(Vec3(174 + 9 * 28, 149, 3600)));
  EXPECT_TRUE(slab.uv.camera_center(9, 0).isApprox(Vec3(174, 149 + 9 * 28, 3600)));
  EXPECT_TRUE(slab.uv.center().isApprox(Vec3(300, 275, 3600)));
  EXPECT_DOUBLE_EQ(slab.separation_mm(), 3600);
}

TEST(Slab, IntersectionGivesWindowCoordinatesOnBothPlanes) {
  const Slab slab = PaperLikeSlab();
  // The line from camera (2, 7)'s centre to the board point (150, 440, 0).
  const Vec3 from = slab.uv.camera_center(2, 7);
  const auto c = slab.intersect({from, Vec3(150, 440, 0) - from});
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->u, 0.75, 1e-12);
  EXPECT_NEAR(c->v, 0.25, 1e-12);
  EXPECT_NEAR(c->s, 150.0 / 600, 1e-12);
  EXPECT_NEAR(c->t, 440.0 / 550, 1e-12);
  EXPECT_TRUE(slab.contains(*c));
  // The direction of travel does not matter: it is the same line.
  const auto back = slab.intersect({from, from - Vec3(150, 440, 0)});
  EXPECT_NEAR(back->s, c->s, 1e-12);
}

TEST(Slab, OutsideTheWindowsIsNotContained) {
  Slab slab = PaperLikeSlab();
  const Vec3 eye(100, 275, 3600);  // left of the array
  const auto c = slab.intersect({eye, Vec3(300, 275, 0) - eye});
  ASSERT_TRUE(c.has_value());
  EXPECT_LT(c->u, 0);
  EXPECT_FALSE(slab.contains(*c));
  slab.st_domain = {-1.2, -1.2, 1.2, 1.2};
  const auto wide = slab.intersect({slab.uv.center(), Vec3(-500, -500, 0) - slab.uv.center()});
  EXPECT_TRUE(slab.contains(*wide));
  EXPECT_FALSE(slab.intersect({eye, Vec3(1, 0, 0)}).has_value());  // parallel to both planes
}

TEST(Slab, JsonRoundTripUsesThePapersNames) {
  Slab slab = PaperLikeSlab();
  slab.st_domain = {-0.2, -0.1, 1.2, 1.1};
  const nlohmann::json j = slab;
  for (const char* key : {"p_ca", "u_ca", "v_ca", "n_ca", "rows", "cols", "pitch_mm"})
    EXPECT_TRUE(j.contains(key)) << key;
  const Slab back = j.get<Slab>();
  EXPECT_TRUE(back.uv.p_ca.isApprox(slab.uv.p_ca));
  EXPECT_DOUBLE_EQ(back.st_domain.s0, -0.2);
  EXPECT_DOUBLE_EQ(back.st.height_mm, 550);
}

TEST(Slab, DegenerateGeometryIsRejectedByName) {
  Slab slab = PaperLikeSlab();
  slab.uv.u_ca = Vec3(1, 1, 0);
  try {
    slab.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("u_ca"), std::string::npos) << e.what();
  }
  slab = PaperLikeSlab();
  slab.uv.u_ca = -Vec3::UnitX();  // left-handed
  EXPECT_THROW(slab.validate(), Error);
  slab = PaperLikeSlab();
  slab.st_domain = {1, 0, 0, 1};
  EXPECT_THROW(slab.validate(), Error);
}

}  // namespace
}  // namespace lfcam

namespace lfcam {
namespace {

TEST(SlabBounds, AbsurdGeometryIsRefused) {
  const auto refused = [](const std::function<void(Slab&)>& edit) {
    Slab slab;
    slab.uv.p_ca = Vec3(0, 0, 3600);
    edit(slab);
    try {
      slab.validate();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(refused([](Slab&) {}), "");
  EXPECT_NE(refused([](Slab& s) { s.uv.p_ca.x() = 1e300; }).find("p_ca"), std::string::npos);
  EXPECT_NE(refused([](Slab& s) { s.uv.pitch_mm = 1e300; }).find("pitch_mm"), std::string::npos);
  EXPECT_NE(refused([](Slab& s) { s.st.width_mm = 1e-30; }).find("width"), std::string::npos);
  EXPECT_NE(refused([](Slab& s) { s.st_domain.s1 = 1e308; }).find("st domain"), std::string::npos);
  EXPECT_NE(refused([](Slab& s) { s.st.origin.z() = NAN; }).find("origin"), std::string::npos);
}

TEST(Color, NonFiniteLinearValuesEncodeWithoutUndefinedCasts) {
  EXPECT_EQ(LinearToSrgb8(std::nanf("")), 0);
  EXPECT_EQ(LinearToSrgb8(-INFINITY), 0);
  EXPECT_EQ(LinearToSrgb8(INFINITY), 255);
  EXPECT_EQ(LinearToSrgb8(2.0f), 255);
  EXPECT_EQ(LinearToSrgb8(0.0f), 0);
  for (const float x : {std::nanf(""), -INFINITY, INFINITY, 2.0f, 0.0f, -1.0f})
    EXPECT_EQ(LinearToSrgb8Exact(x), LinearToSrgb8(x)) << x;
}

// The bulk encoder (every image lfcam writes) is LinearToSrgb8 exactly: on every code's step
// and its float neighbours, and on a dense sweep of [0, 1] (every 2^-24).
TEST(Color, BulkEncodingIsExactlyLinearToSrgb8) {
  for (int i = 0; i <= (1 << 24); ++i) {
    const float x = float(i) / float(1 << 24);
    ASSERT_EQ(LinearToSrgb8Exact(x), LinearToSrgb8(x)) << x;
  }
  for (int c = 0; c < 255; ++c) {
    // Where the code steps from c to c + 1 (bisected here too, on doubles).
    double lo = 0, hi = 1;
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      (LinearToSrgb8(float(mid)) > c ? hi : lo) = mid;
    }
    for (float x = std::nextafter(float(lo), 0.0f), n = 0; n < 4; ++n, x = std::nextafter(x, 2.0f))
      ASSERT_EQ(LinearToSrgb8Exact(x), LinearToSrgb8(x)) << x;
  }
}

}  // namespace
}  // namespace lfcam
