#include "lfcam/render/camera_path.h"

#include <gtest/gtest.h>

#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

VirtualCameraParams View(const Vec3& eye, double focus, double aperture) {
  VirtualCameraParams p;
  p.width = 320;
  p.height = 240;
  p.eye = eye;
  p.look_at = eye - Vec3(0, 0, 1000);
  p.focus_distance_mm = focus;
  p.aperture_mm = aperture;
  return p;
}

TEST(CameraPath, ASweepGoesLinearlyFromAToB) {
  CameraSweep sweep;
  sweep.focus_distance_mm = {{3400.0, 5200.0}};
  sweep.eye = {{Vec3(-100, 0, 3600), Vec3(100, 0, 3600)}};
  const CameraPath path = CameraPath::Sweep(View(Vec3::Zero(), 4000, 64), sweep);
  EXPECT_DOUBLE_EQ(path.AtFrame(0, 7).focus_distance_mm, 3400.0);
  EXPECT_DOUBLE_EQ(path.AtFrame(3, 7).focus_distance_mm, 4300.0);
  EXPECT_DOUBLE_EQ(path.AtFrame(6, 7).focus_distance_mm, 5200.0);
  EXPECT_TRUE(path.AtFrame(3, 7).eye.isApprox(Vec3(0, 0, 3600)));
  EXPECT_DOUBLE_EQ(path.AtFrame(2, 7).aperture_mm, 64.0) << "what is not swept stays";
  EXPECT_FALSE(path.is_fixed());
  EXPECT_TRUE(CameraPath::Fixed(View(Vec3::Zero(), 4000, 0)).is_fixed());
}

TEST(CameraPath, ThroughViewsPassesThroughEveryViewSmoothly) {
  const std::vector<VirtualCameraParams> views = {View(Vec3(0, 0, 0), 3400, 64),
                                                  View(Vec3(100, 50, 0), 4000, 128),
                                                  View(Vec3(200, 0, 0), 5000, 64)};
  const CameraPath path = CameraPath::ThroughViews(views, {"a.json", "b.json", "c.json"});
  for (int i = 0; i < 3; ++i) {
    const VirtualCameraParams p = path.At(i / 2.0);
    EXPECT_TRUE(p.eye.isApprox(views[i].eye, 1e-12) || p.eye.norm() + views[i].eye.norm() < 1e-9)
        << i;
    EXPECT_DOUBLE_EQ(p.focus_distance_mm, views[i].focus_distance_mm) << i;
    EXPECT_DOUBLE_EQ(p.aperture_mm, views[i].aperture_mm) << i;
  }
  EXPECT_DOUBLE_EQ(path.At(0.25).focus_distance_mm, 3700.0) << "the lens is linear in a leg";
  // The eye's velocity is continuous through the middle view (no corner), and the curve bulges
  // past the middle view's height on neither leg by much (Catmull-Rom, not a wild polynomial).
  const double h = 1e-6;
  const Vec3 before = (path.At(0.5).eye - path.At(0.5 - h).eye) / h;
  const Vec3 after = (path.At(0.5 + h).eye - path.At(0.5).eye) / h;
  EXPECT_LT((before - after).norm(), 1e-3 * before.norm());
  for (double u = 0; u <= 1.0; u += 0.01) EXPECT_LE(path.At(u).eye.y(), 50.0 * 1.15);
  // Two views: a straight line at an even pace.
  const CameraPath line = CameraPath::ThroughViews({views[0], views[2]}, {});
  EXPECT_TRUE(line.At(0.25).eye.isApprox(Vec3(50, 0, 0), 1e-12));
  EXPECT_TRUE(line.At(0.5).eye.isApprox(Vec3(100, 0, 0), 1e-12));
}

TEST(CameraPath, ViewsThatCannotShareAVideoAreNamed) {
  std::vector<VirtualCameraParams> views = {View(Vec3::Zero(), 4000, 0),
                                            View(Vec3(1, 0, 0), 4000, 0)};
  views[1].width = 640;
  EXPECT_NE(testing::ErrorOf([&] {
              CameraPath::ThroughViews(views, {"a.json", "b.json"});
            }).find("b.json: camera.width/height 640x240"),
            std::string::npos);
  views[1].width = 320;
  views[1].breathing = false;
  EXPECT_NE(testing::ErrorOf([&] {
              CameraPath::ThroughViews(views, {"a.json", "b.json"});
            }).find("b.json: camera.breathing"),
            std::string::npos);
  EXPECT_NE(testing::ErrorOf([&] { CameraPath::ThroughViews({views[0]}, {}); }).find("two views"),
            std::string::npos);
}

}  // namespace
}  // namespace lfcam
