#include "lfcam/core/geometry.h"

#include <gtest/gtest.h>

#include <numbers>

namespace lfcam {
namespace {

TEST(Plane, IntersectsLinesAndRejectsParallelOnes) {
  const Plane board{Vec3::Zero(), Vec3::UnitZ()};
  const Ray ray{Vec3(10, 20, 3600), Vec3(1, -1, -2)};
  const auto t = board.intersect(ray);
  ASSERT_TRUE(t.has_value());
  EXPECT_TRUE(ray.at(*t).isApprox(Vec3(1810, -1780, 0)));
  EXPECT_DOUBLE_EQ(board.signed_distance(ray.origin), 3600);
  EXPECT_FALSE(board.intersect({Vec3(0, 0, 5), Vec3(1, 2, 0)}).has_value());
}

TEST(Rigid3, ComposesAndInvertsByFrames) {
  // camera -> array: a quarter turn about z and a shift; array -> world: a shift.
  Rigid3 array_from_camera;
  array_from_camera.rotation = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()).matrix();
  array_from_camera.translation = Vec3(28, 0, 0);
  Rigid3 world_from_array;
  world_from_array.translation = Vec3(160, 135, 3600);
  const Rigid3 world_from_camera = world_from_array * array_from_camera;
  const Vec3 x_camera(1, 2, 3);
  EXPECT_TRUE((world_from_camera * x_camera).isApprox(Vec3(160 + 28 - 2, 135 + 1, 3603)));
  EXPECT_TRUE((world_from_camera.inverse() * (world_from_camera * x_camera)).isApprox(x_camera));
  const Rigid3 identity = world_from_camera * world_from_camera.inverse();
  EXPECT_TRUE(identity.rotation.isApprox(Mat3::Identity()));
  EXPECT_LT(identity.translation.norm(), 1e-9);
}

}  // namespace
}  // namespace lfcam
