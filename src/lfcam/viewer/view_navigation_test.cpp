// The viewer's navigation as pure functions of the camera: orbiting keeps the point in focus
// where it is, panning and moving translate without turning, zoom and focus stay valid.
#include "lfcam/viewer/view_navigation.h"

#include <gtest/gtest.h>

namespace lfcam {
namespace {

VirtualCameraParams Start() {
  VirtualCameraParams p;
  p.width = 640;
  p.height = 480;
  p.eye = Vec3(300, 275, 3600);
  p.look_at = Vec3(300, 275, 0);
  p.focal_length_mm = 300;
  p.focus_distance_mm = 3900;
  return p;
}

Vec3 Pivot(const VirtualCameraParams& p) {
  const VirtualCamera c(p);
  return c.e_c() + p.focus_distance_mm * (-c.n_c());
}

TEST(ViewNavigation, OrbitTurnsAroundThePointInFocus) {
  const VirtualCameraParams p = Start();
  const VirtualCameraParams q = Orbit(p, 0.2, -0.1);
  EXPECT_LT((Pivot(q) - Pivot(p)).norm(), 1e-6);
  EXPECT_NEAR((q.eye - Pivot(q)).norm(), p.focus_distance_mm, 1e-6);
  EXPECT_GT((q.eye - p.eye).norm(), 100.0);
  // A positive yaw swings the eye to the left so the camera turns right, toward +x here.
  const VirtualCamera turned(q);
  EXPECT_GT((-turned.n_c()).x(), 0.1);
  // Positive pitch looks up.
  const VirtualCamera up(Orbit(p, 0, 0.1));
  EXPECT_GT((-up.n_c()).y(), 0.05);
  // Turning there and back returns.
  const VirtualCameraParams back = Orbit(Orbit(p, 0.3, 0), -0.3, 0);
  EXPECT_LT((back.eye - p.eye).norm(), 1e-6);
}

TEST(ViewNavigation, MoveAndPanTranslateWithoutTurning) {
  const VirtualCameraParams p = Start();
  const VirtualCameraParams q = Move(p, 10, -5, 100);
  EXPECT_LT((q.eye - (p.eye + Vec3(10, -5, -100))).norm(), 1e-9);
  EXPECT_LT(((q.look_at - q.eye) - (p.look_at - p.eye)).norm(), 1e-9);
  // One pixel at the plane of focus: d_o * 56 / (f * width) with breathing's film at d_i.
  const double mm = MmPerPixelAtFocus(p);
  const double d_i = ThinLensImageDistance(p.focal_length_mm, p.focus_distance_mm);
  EXPECT_NEAR(mm, p.focus_distance_mm * kFilmSizeMm / d_i / p.width, 1e-9);
}

TEST(ViewNavigation, ZoomFocusAndResetStayValid) {
  VirtualCameraParams p = Start();
  for (int i = 0; i < 100; ++i) p = ScaleFocalLength(p, 1.5);
  EXPECT_LT(p.focal_length_mm, p.focus_distance_mm);
  EXPECT_NO_THROW(VirtualCamera{p});
  for (int i = 0; i < 100; ++i) p = ScaleFocusDistance(p, 0.5);
  EXPECT_GT(p.focus_distance_mm, p.focal_length_mm);
  EXPECT_NO_THROW(VirtualCamera{p});
  ArrayPlane array;
  array.rows = array.cols = 10;
  array.pitch_mm = 28;
  array.p_ca = Vec3(0, 0, 3600);
  const VirtualCameraParams r = ResetToArrayCentre(Orbit(p, 0.5, 0.2), array);
  EXPECT_LT((r.eye - array.center()).norm(), 1e-9);
  EXPECT_LT(((r.look_at - r.eye).normalized() + array.n_ca).norm(), 1e-9);
}

}  // namespace
}  // namespace lfcam
