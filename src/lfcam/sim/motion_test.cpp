#include "lfcam/sim/motion.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/sim/scene.h"

namespace lfcam {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Motion, SpinsAboutItsPivotThenMoves) {
  Motion m;
  m.pivot = Vec3(10, 0, 0);
  m.axis = Vec3::UnitZ();
  m.spin_rad_per_s = kPi / 2;  // a quarter turn a second
  m.velocity_mm_per_s = Vec3(0, 0, -5);
  EXPECT_TRUE(m.PointAt(Vec3(20, 0, 0), 0).isApprox(Vec3(20, 0, 0)));
  // After a second: (20, 0, 0) a quarter turn counter-clockwise about (10, 0, z), then 5 mm down.
  EXPECT_TRUE(m.PointAt(Vec3(20, 0, 0), 1).isApprox(Vec3(10, 10, -5), 1e-12));
  EXPECT_TRUE(m.PointAt(m.pivot, 3).isApprox(m.pivot + Vec3(0, 0, -15), 1e-12));
}

TEST(Motion, AMovedShapeIsHitWhereItWentAndKeepsItsTexture) {
  const auto sphere = std::make_shared<SphereShape>(Vec3(0, 0, -100), 10);
  Motion m;
  m.velocity_mm_per_s = Vec3(30, 0, 0);
  const MovedShape moved(sphere, m.At(2.0));  // 60 mm to the right
  SurfaceHit hit;
  EXPECT_FALSE(moved.Intersect({Vec3::Zero(), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));
  ASSERT_TRUE(moved.Intersect({Vec3(60, 0, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));
  EXPECT_NEAR(hit.t, 90, 1e-9);
  EXPECT_TRUE(hit.normal.isApprox(Vec3(0, 0, 1)));
  // A disc turned a quarter about its normal: its texture coordinates turn with it.
  const auto disc = std::make_shared<DiscShape>(Vec3(0, 0, -50), Vec3::UnitZ(), 20);
  SurfaceHit still, turned;
  ASSERT_TRUE(disc->Intersect({Vec3(10, 0, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &still));
  Motion spin;
  spin.axis = Vec3::UnitZ();
  spin.spin_rad_per_s = kPi / 2;
  const MovedShape quarter(disc, spin.At(1.0));
  // The point that was at (10, 0) is now at (0, 10): the same texture there.
  ASSERT_TRUE(quarter.Intersect({Vec3(0, 10, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &turned));
  EXPECT_NEAR((turned.uv_mm - still.uv_mm).norm(), 0.0, 1e-9);
}

// The paper scene at a time: the fan turns, the ball flies across the scene at 400 mm/s, the
// bead whirls; a still of the scene is the scene at no time, without them.
TEST(PaperScene, AtATimeTheBallIsWhereItsSpeedPutsIt) {
  const Scene still = MakePaperScene();
  EXPECT_TRUE(still.moves());
  for (const SceneObject& o : still.objects) EXPECT_NE(o.name, "ball");
  const Scene at_1s = still.AtTime(1.0), at_2s = still.AtTime(2.0);
  EXPECT_FALSE(at_1s.moves());  // a scene at a time is a still of its own
  const auto ball = [](const Scene& s) {
    for (std::size_t i = 0; i < s.objects.size(); ++i)
      if (s.objects[i].name == "ball") return int(i);
    return -1;
  };
  ASSERT_GE(ball(at_1s), 0);
  // The ball's centre at t: x = -150 + 400 t, 360 mm above the table (y = 435), 4.3 m from the
  // array (z = -700); seen from the array's side, its nearest point is 40 mm nearer.
  for (const auto& [scene, x] : {std::pair{&at_1s, 250.0}, std::pair{&at_2s, 650.0}}) {
    const Ray ahead{Vec3(x, 435, 3600), Vec3(0, 0, -1)};
    const Scene::Hit hit = scene->FirstHit(ahead);
    ASSERT_EQ(hit.object, ball(*scene)) << x;
    EXPECT_NEAR(ahead.at(hit.t).z(), -700 + 40, 1e-6);
    EXPECT_NE(still.FirstHit(ahead).object, hit.object);
  }
  // Rays that meet no mover see the same at any time; the fan's texture turns.
  const Ray at_wall{Vec3(300, 600, 3600), Vec3(0, 0, -1)};
  EXPECT_TRUE(still.Radiance(at_wall).isApprox(at_1s.Radiance(at_wall)));
  const Ray at_fan{Vec3(420 + 60, 75 + 250 + 25, 3600), Vec3(0, 0, -1)};
  bool changed = false;
  for (const double t : {0.02, 0.03, 0.07})  // not multiples of a fifth of a turn (5 blades)
    changed |= !still.Radiance(at_fan).isApprox(still.AtTime(t).Radiance(at_fan), 1e-6);
  EXPECT_TRUE(changed) << "the fan should turn";
  EXPECT_TRUE(still.Radiance(at_fan).isApprox(still.AtTime(0.5).Radiance(at_fan), 1e-9))
      << "after a whole turn (2 revolutions a second) the fan looks as at t = 0";
}

}  // namespace
}  // namespace lfcam
