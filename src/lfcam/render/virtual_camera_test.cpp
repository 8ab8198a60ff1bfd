#include "lfcam/render/virtual_camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

VirtualCameraParams Params(double f, double d_o, bool breathing) {
  VirtualCameraParams p;
  p.width = p.height = 1024;
  p.eye = Vec3(300, 275, 3600);
  p.look_at = Vec3(300, 275, 0);
  p.focal_length_mm = f;
  p.focus_distance_mm = d_o;
  p.breathing = breathing;
  return p;
}

TEST(ThinLens, ImageDistanceSatisfiesTheLensEquation) {
  for (double f : {444.0, 500.0, 1000.0})
    for (double d_o : {3400.0, 3900.0, 5200.0}) {
      const double d_i = ThinLensImageDistance(f, d_o);
      EXPECT_NEAR(1 / d_i + 1 / d_o, 1 / f, 1e-15);
      const double f_e = EffectiveFocalLength(f, d_o);
      // Non-breathing: the film stays at f, so 1/f + 1/d_o = 1/f_e.
      EXPECT_NEAR(1 / f + 1 / d_o, 1 / f_e, 1e-15);
    }
}

TEST(VirtualCamera, BreathingFieldOfViewIsThePapers) {
  // 2 atan(56 (d_o - f) / (2 d_o f)), e.g. f = 500, d_o = 3400.
  const VirtualCamera camera(Params(500, 3400, true));
  const double expected = 2 * std::atan(56.0 * (3400 - 500) / (2.0 * 3400 * 500));
  EXPECT_NEAR(camera.field_of_view_rad(), expected, 1e-12);
  EXPECT_NEAR(BreathingFieldOfView(500, 3400), expected, 1e-12);
  // Focusing farther widens the field (the film moves toward the lens).
  EXPECT_GT(VirtualCamera(Params(500, 5200, true)).field_of_view_rad(), expected);
}

TEST(VirtualCamera, NonBreathingFieldOfViewIsFixed) {
  const double expected = 2 * std::atan(56.0 / (2 * 500));
  for (double d_o : {3400.0, 4300.0, 5200.0}) {
    const VirtualCamera camera(Params(500, d_o, false));
    EXPECT_NEAR(camera.field_of_view_rad(), expected, 1e-12);
    EXPECT_NEAR(camera.lens_focal_length_mm(), 500 * d_o / (500 + d_o), 1e-9);
    EXPECT_NEAR(camera.film_distance_mm(), 500, 1e-12);
  }
}

TEST(VirtualCamera, PixelDirectionsFollowThePapersFormula) {
  const VirtualCamera camera(Params(500, 4000, true));
  const double tan_half = std::tan(camera.field_of_view_rad() / 2);
  const int n = 1024;
  for (auto [i, j] : {std::pair{0, 0}, {1023, 0}, {17, 900}, {511, 512}}) {
    const Vec3 expected = -camera.n_c() + tan_half * ((2.0 * i + 1) / n - 1) * camera.u_c() +
                          tan_half * ((2.0 * j + 1) / n - 1) * camera.v_c();
    EXPECT_TRUE(camera.pixel_direction(i, j).isApprox(expected, 1e-12));
  }
  // Looking down -z from the array: u_c = +x (right), v_c = +y (up), pixel (0, 0) bottom left.
  EXPECT_TRUE(camera.u_c().isApprox(Vec3::UnitX()));
  EXPECT_TRUE(camera.v_c().isApprox(Vec3::UnitY()));
  EXPECT_TRUE(camera.n_c().isApprox(Vec3::UnitZ()));
  EXPECT_LT(camera.pixel_direction(0, 0).x(), 0);
  EXPECT_LT(camera.pixel_direction(0, 0).y(), 0);
  EXPECT_EQ(camera.image_row(0), 1023);
}

TEST(VirtualCamera, FocusPointLiesOnThePlaneOfFocus) {
  const VirtualCamera camera(Params(500, 4300, true));
  for (auto [i, j] : {std::pair{0, 0}, {800, 100}}) {
    const Vec3 p_o = camera.focus_point(camera.pixel_direction(i, j));
    EXPECT_NEAR((camera.e_c() - p_o).dot(camera.n_c()), 4300, 1e-9);
  }
}

TEST(VirtualCamera, LensSamplesScaleWithTheAperture) {
  auto p = Params(444, 4000, true);
  EXPECT_EQ(VirtualCamera(p).lens_samples().size(), 1u);  // pinhole
  p.aperture_mm = 128;
  p.lens_rate = 4;
  const VirtualCamera camera(p);
  EXPECT_EQ(camera.lens_samples().size(), 78u);  // 4 * 64^2 / 210 = 78.02
  for (const Vec2& s : camera.lens_samples()) {
    const Vec3 lens = camera.lens_point(s);
    EXPECT_LE((lens - camera.e_c()).norm(), 64 + 1e-9);
    EXPECT_NEAR((lens - camera.e_c()).dot(camera.n_c()), 0, 1e-9);
  }
}

TEST(VirtualCamera, BadParametersAreRejected) {
  auto p = Params(500, 400, true);  // focus closer than f
  EXPECT_THROW(VirtualCamera{p}, Error);
  p = Params(500, 4000, true);
  p.up = Vec3(0, 0, 1);  // parallel to the view direction
  EXPECT_THROW(VirtualCamera{p}, Error);
  p = Params(500, 4000, true);
  p.aperture_mm = -1;
  EXPECT_THROW(VirtualCamera{p}, Error);
  p = Params(500, 4000, true);
  p.look_at = p.eye;
  EXPECT_THROW(VirtualCamera{p}, Error);
  // Without breathing the film stays at f: any focus in front of the lens will do.
  p = Params(500, 400, false);
  EXPECT_NO_THROW(VirtualCamera{p});
  p.principal_offset_px = Vec2(1e9, 0);
  EXPECT_THROW(VirtualCamera{p}, Error);
}

// A shifted film (an off-axis camera, as a rectified rig's) moves every pixel's ray by the
// offset, and a resized frame keeps each ray where it was.
TEST(VirtualCamera, PrincipalOffsetShiftsTheFilmAndScalesWithTheFrame) {
  auto p = Params(56, 4000, false);
  p.width = 200;
  p.height = 100;
  const VirtualCamera centred(p);
  p.principal_offset_px = Vec2(12.5, -7.0);
  const VirtualCamera shifted(p);
  EXPECT_LT(
      (shifted.direction_through(40 + 12.5, 30 - 7.0) - centred.direction_through(40, 30)).norm(),
      1e-12);
  // The optical axis meets the film at its centre plus the offset.
  EXPECT_LT((shifted.direction_through(100 + 12.5, 50 - 7.0) + shifted.n_c()).norm(), 1e-12);
  const VirtualCamera doubled(WithFrameSize(p, 400, 200));
  EXPECT_LT(
      (doubled.direction_through(80 + 25, 60 - 14) - shifted.direction_through(40 + 12.5, 30 - 7.0))
          .norm(),
      1e-12);
  EXPECT_EQ(MinFocusDistance(p), 1e-3);
  p.breathing = true;
  EXPECT_DOUBLE_EQ(MinFocusDistance(p), 1.05 * 56);
}

}  // namespace
}  // namespace lfcam
