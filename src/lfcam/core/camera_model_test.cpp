#include "lfcam/core/camera_model.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

CameraIntrinsics PiLike() {
  CameraIntrinsics c;
  c.width = 2592;
  c.height = 1944;
  c.fx = 2560;
  c.fy = 2565;
  c.cx = 1305;
  c.cy = 960;
  c.distortion = {0.11, -0.23, 0.001, -0.0012, 0.08};
  return c;
}

TEST(CameraModel, ProjectsAndUnprojectsEveryPixelBack) {
  const CameraIntrinsics c = PiLike();
  for (int y = 0; y < c.height; y += 97)
    for (int x = 0; x < c.width; x += 101) {
      const auto ray = c.Unproject(Vec2(x, y));
      ASSERT_TRUE(ray) << x << "," << y;
      const auto back = c.Project(*ray * 3.7);
      ASSERT_TRUE(back);
      EXPECT_NEAR((*back - Vec2(x, y)).norm(), 0, 1e-7) << x << "," << y;
    }
  EXPECT_FALSE(c.Project(Vec3(0, 0, -1)));  // behind the camera
}

TEST(CameraModel, DistortionMatchesOpenCvsFormula) {
  const Distortion d{0.1, -0.2, 0.003, -0.002, 0.05};
  const Vec2 p(0.3, -0.2);
  const double r2 = p.squaredNorm();
  const double radial = 1 + 0.1 * r2 - 0.2 * r2 * r2 + 0.05 * r2 * r2 * r2;
  const Vec2 expected(
      p.x() * radial + 2 * 0.003 * p.x() * p.y() - 0.002 * (r2 + 2 * p.x() * p.x()),
      p.y() * radial + 0.003 * (r2 + 2 * p.y() * p.y()) - 2 * 0.002 * p.x() * p.y());
  EXPECT_NEAR((d.Apply(p) - expected).norm(), 0, 1e-15);
  const auto undone = d.Remove(d.Apply(p));
  ASSERT_TRUE(undone);
  EXPECT_NEAR((*undone - p).norm(), 0, 1e-12);
}

TEST(CameraModel, WorldFromCameraLooksAlongMinusN) {
  const Mat3 r = WorldFromCameraRotation(Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ());
  EXPECT_EQ(r * Vec3(0, 0, 1), Vec3(0, 0, -1));  // forward: toward the scene
  EXPECT_EQ(r * Vec3(0, -1, 0), Vec3(0, 1, 0));  // image up: world up
  EXPECT_NEAR(r.determinant(), 1, 1e-15);
  const Vec3 aa(0.1, -0.2, 0.3);
  EXPECT_NEAR((AngleAxisFromRotation(RotationFromAngleAxis(aa)) - aa).norm(), 0, 1e-12);
}

TEST(CameraModel, JsonRoundTripAndRefusals) {
  const CameraIntrinsics c = PiLike();
  const CameraIntrinsics back = IntrinsicsFromJson(IntrinsicsToJson(c), "camera");
  EXPECT_EQ(back.fx, c.fx);
  EXPECT_EQ(back.cy, c.cy);
  EXPECT_EQ(back.distortion.p2, c.distortion.p2);
  auto j = IntrinsicsToJson(c);
  j["fx"] = -5;
  EXPECT_THROW(IntrinsicsFromJson(j, "camera"), Error);
  j = IntrinsicsToJson(c);
  j["distortion"] = {1, 2, 3};
  EXPECT_THROW(IntrinsicsFromJson(j, "camera"), Error);
  j = IntrinsicsToJson(c);
  j["width"] = 1e9;
  EXPECT_THROW(IntrinsicsFromJson(j, "camera"), Error);
  const Mat3 r = RotationFromAngleAxis(Vec3(0.2, 0.1, -0.4));
  EXPECT_NEAR((RotationFromJson(RotationToJson(r), "r") - r).norm(), 0, 1e-15);
  EXPECT_THROW(RotationFromJson(RotationToJson(2 * r), "r"), Error);
  EXPECT_THROW(RotationFromJson(RotationToJson(-r), "r"), Error);  // determinant -1
}

}  // namespace
}  // namespace lfcam
