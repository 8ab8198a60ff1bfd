#include "lfcam/sim/capture_simulation.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "lfcam/sim/board_radiance.h"
#include "lfcam/sim/camera_module.h"

namespace lfcam {
namespace {

// Every shape's bounding sphere holds every point of the shape that a ray finds.
TEST(BoundingSphere, HoldsEveryHitOfItsShape) {
  const Scene scene = MakeScene("paper").AtTime(0.37);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const SceneObject& o : scene.objects) {
    const BoundingSphere b = o.shape->Bounds();
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
      // Rays from a point outside the sphere toward a point inside it.
      const Vec3 from = b.center + 3 * b.radius * Vec3(u(rng), u(rng), u(rng)).normalized();
      const Vec3 to = b.center + b.radius * Vec3(u(rng), u(rng), u(rng));
      SurfaceHit hit;
      if (!o.shape->Intersect({from, (to - from).normalized()}, 1e-9, 1e9, &hit)) continue;
      ++hits;
      const Vec3 p = from + hit.t * (to - from).normalized();
      ASSERT_LE((p - b.center).norm(), b.radius * (1 + 1e-9)) << o.name;
    }
    EXPECT_GT(hits, 100) << o.name;
  }
}

// A video frame traces again only what may have moved: with an ideal sensor it is exactly the
// scene at that time rendered in full, and the ball it shows is not in the still.
TEST(SimulatedArray, AVideoFrameIsTheSceneAtItsTime) {
  const Scene scene = MakeScene("paper");
  CaptureSimulationOptions o;
  o.rows = o.cols = 3;
  o.sensor_width = 160;
  o.sensor_height = 120;
  o.noise = false;
  o.intrinsics_shots = 1;
  const SimulatedArray array(scene, o);
  const std::size_t module = *array.module_at(1, 1);
  const SimulatedModule& m = array.modules()[module];
  const cv::Mat directions = ModuleRayDirections(m);
  SimulatedArray::ModuleCache cache;
  const cv::Mat still = array.Expose(module, *array.shot_named("scene"), cache);
  for (const double t : {0.0, 0.8, 1.1}) {
    const Scene at = scene.AtTime(t);
    const cv::Mat full = ExposeRadiance(
        m, RenderRadiance(m, directions, SceneRadiance(at, o.scene_supersampling)), {false});
    const cv::Mat frame = array.ExposeAt(module, t, 3, cache);
    EXPECT_EQ(cv::norm(frame, full, cv::NORM_INF), 0) << "t = " << t;
  }
  // At 1.1 s the ball (x = 290 mm, 80 mm across: 3 pixels here) is in view: the frame differs
  // from the still there.
  const cv::Mat moved = array.ExposeAt(module, 1.1, 3, cache);
  cv::Mat diff;
  cv::absdiff(moved, still, diff);
  cv::Mat gray;
  cv::cvtColor(diff, gray, cv::COLOR_RGB2GRAY);
  EXPECT_GE(cv::countNonZero(gray > 20), 5);
}

}  // namespace
}  // namespace lfcam
