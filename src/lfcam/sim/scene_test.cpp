#include "lfcam/sim/scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

TEST(Shapes, AnalyticIntersections) {
  SurfaceHit hit;
  const SphereShape sphere(Vec3(0, 0, -10), 2);
  ASSERT_TRUE(sphere.Intersect({Vec3::Zero(), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));
  EXPECT_NEAR(hit.t, 8, 1e-12);
  EXPECT_TRUE(hit.normal.isApprox(Vec3(0, 0, 1)));
  EXPECT_FALSE(sphere.Intersect({Vec3::Zero(), Vec3(1, 0, -1)}, 1e-9, 1e9, &hit));

  const BoxShape box(Vec3(-1, -1, -6), Vec3(1, 1, -4));
  ASSERT_TRUE(box.Intersect({Vec3(0.5, 0.2, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));
  EXPECT_NEAR(hit.t, 4, 1e-12);
  EXPECT_TRUE(hit.normal.isApprox(Vec3(0, 0, 1)));
  ASSERT_TRUE(box.Intersect({Vec3(-5, 0, -5), Vec3(1, 0, 0)}, 1e-9, 1e9, &hit));
  EXPECT_NEAR(hit.t, 4, 1e-12);
  EXPECT_TRUE(hit.normal.isApprox(Vec3(-1, 0, 0)));

  const ConeShape cone(Vec3(0, 0, -10), 2, 4);  // apex at y = 4
  ASSERT_TRUE(cone.Intersect({Vec3(0, 2, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));
  EXPECT_NEAR(hit.t, 9, 1e-9);  // radius 1 at half height
  EXPECT_FALSE(cone.Intersect({Vec3(0, 4.5, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));
  ASSERT_TRUE(cone.Intersect({Vec3(0.5, -5, -10), Vec3(0, 1, 0)}, 1e-9, 1e9, &hit));
  EXPECT_NEAR(hit.t, 5, 1e-9);  // the base
  EXPECT_TRUE(hit.normal.isApprox(Vec3(0, -1, 0)));

  const DiscShape disc(Vec3(0, 0, -3), Vec3::UnitZ(), 1);
  EXPECT_TRUE(disc.Intersect({Vec3(0.5, 0.5, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));
  EXPECT_FALSE(disc.Intersect({Vec3(0.9, 0.9, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));

  const RectangleShape rect(Vec3(0, 0, -2), Vec3::UnitX(), Vec3::UnitY(), 1, 0.5);
  EXPECT_TRUE(rect.Intersect({Vec3(0.9, 0.4, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));
  EXPECT_NEAR(hit.uv_mm.x(), 1.9, 1e-12);
  EXPECT_FALSE(rect.Intersect({Vec3(0.9, 0.6, 0), Vec3(0, 0, -1)}, 1e-9, 1e9, &hit));
}

TEST(PaperScene, ObjectsSitAtThePapersDistances) {
  const Scene scene = MakePaperScene();
  const ArrayPlane& array = scene.rig.array;
  EXPECT_EQ(array.rows, 10);
  EXPECT_EQ(array.cols, 10);
  EXPECT_DOUBLE_EQ(array.pitch_mm, 28);
  EXPECT_TRUE(array.center().isApprox(Vec3(300, 275, 3600)));
  // The world board (view window) is 3.6 m from the array, centred in front of it.
  EXPECT_NEAR(array.n_ca.dot(array.center() - scene.rig.board.point_at(0.5, 0.5)), 3600, 1e-9);
  // Straight-ahead rays from the array plane to each object's front surface.
  struct Probe {
    const char* name;
    Vec3 target;
    double metres;
  };
  for (const auto& p :
       {Probe{"coffee maker", Vec3(170, 200, 0), 3.4},
        Probe{"marker cone", Vec3(260, 90, 0), 3.7 - 0.045 * (1 - 15 / 160.0)},
        Probe{"globe", Vec3(370, 165, 0), 3.9 - 0.09}, Probe{"fan", Vec3(420, 325, 0), 4.7},
        Probe{"checkerboard", Vec3(100, 500, 0), 5.2}}) {
    const Vec3 origin(p.target.x(), p.target.y(), 3600);
    EXPECT_NEAR(scene.FirstHitDistance({origin, Vec3(0, 0, -1)}), 1000 * p.metres, 1e-6) << p.name;
  }
  EXPECT_THROW(MakeScene("nonexistent"), Error);
}

TEST(PaperScene, RadianceIsFiniteAndTexturesVary) {
  const Scene scene = MakePaperScene();
  const Vec3 eye = scene.rig.array.center();
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < 200; ++i) {
    const Vec3 target(100 + 2.0 * i, 100 + 1.5 * i, 0);
    const Vec3 L = scene.Radiance({eye, target - eye});
    ASSERT_TRUE(L.allFinite());
    EXPECT_GE(L.minCoeff(), 0);
    lo = std::min(lo, L.sum());
    hi = std::max(hi, L.sum());
  }
  EXPECT_GT(hi - lo, 0.5);  // real texture, not a flat colour
}

}  // namespace
}  // namespace lfcam
