// Click to focus against the simulator's truth: the plane sweep's focus distance at a pixel
// against the distance of the first surface the pixel's central ray meets in the scene.
#include "lfcam/render/focus_probe.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <string>

#include "lfcam/core/view_filling.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam {
namespace {

const Scene& PaperScene() {
  static const Scene scene = MakePaperScene();
  return scene;
}

// The paper's array, 10 x 10 views of 312 x 288 samples over the world board.
const LightField& FocusProbeLightField() {
  static const LightField lf = [] {
    SimulateLightFieldOptions o;
    o.n_s = 312;
    o.n_t = 288;
    o.supersampling = 1;
    return SimulateLightField(PaperScene(), o);
  }();
  return lf;
}

// The true focus distance at film position (x, y): the first hit along the central ray,
// measured along -n_c.
double TrueFocusDistance(const VirtualCamera& camera, double x, double y) {
  const Vec3 direction = camera.direction_through(x, y);
  const double t = PaperScene().FirstHitDistance(Ray{camera.e_c(), direction.normalized()});
  return t * direction.normalized().dot(-camera.n_c());
}

struct Target {
  std::string name;
  Vec3 point;  // looked at: it falls on the frame's centre
};

TEST(FocusProbe, FindsTheDistanceOfWhatThePixelSees) {
  const LightField& lf = FocusProbeLightField();
  const Vec3 centre = lf.slab().uv.center();
  // Points on the objects' fronts (the paper scene's layout: z = 3600 - distance).
  const Target targets[] = {{"globe", Vec3(370, 165, -300 + 40)},
                            {"marker cone", Vec3(260, 130, -100)},
                            {"coffee maker", Vec3(170, 180, 200)},
                            {"checkerboard", Vec3(240, 300, -1600)}};
  for (const Vec3& eye : {centre, Vec3(centre + Vec3(40, -30, -500))}) {
    for (const Target& target : targets) {
      VirtualCameraParams p;
      p.width = p.height = 256;
      p.eye = eye;
      p.look_at = target.point;
      p.focal_length_mm = 300;
      const VirtualCamera camera(p);
      const double truth = TrueFocusDistance(camera, 128, 128);
      ASSERT_TRUE(std::isfinite(truth)) << target.name;
      const FocusProbe probe = ProbeFocusDistance(lf, camera, 128, 128);
      ASSERT_TRUE(probe.found) << target.name;
      EXPECT_NEAR(probe.focus_distance_mm, truth, 0.02 * truth)
          << target.name << " from eye z " << eye.z();
      EXPECT_GT(probe.confidence, 0.5) << target.name;
      EXPECT_GT(probe.cameras, 50) << target.name;
      std::cout << target.name << " from eye z " << eye.z() << ": " << probe.focus_distance_mm
                << " mm, true " << truth << " mm (" << 100 * (probe.focus_distance_mm / truth - 1)
                << "%), confidence " << probe.confidence << "\n";
    }
  }
}

// Cameras the light field filled from their neighbours (a dead camera of the array, built with
// --allow-missing) are no photographs: the probe compares the photographed cameras alone, and
// still finds what the pixel sees.
TEST(FocusProbe, ComparesThePhotographedCamerasAlone) {
  const LightField& whole = FocusProbeLightField();
  LightField lf(whole.dims(), whole.sample_type(), whole.slab());
  std::memcpy(lf.mutable_view_data(0, 0), whole.data(), whole.total_bytes());
  nlohmann::json filled = nlohmann::json::array();
  std::vector<bool> present(lf.dims().view_count(), true);
  for (int i = 0; i < 10; ++i) present[std::size_t((i % 5) * 2 * 10 + (3 * i) % 10)] = false;
  for (int r = 0; r < 10; ++r)
    for (int c = 0; c < 10; ++c) {
      if (present[std::size_t(r * 10 + c)]) continue;
      const auto from = NearestPresentViews(10, 10, present, r, c);
      FillViewWithMean(lf, r, c, from);
      filled.push_back({{"row", r}, {"col", c}, {"from", from}});
    }
  lf.metadata()["filled_views"] = filled;
  ASSERT_EQ(FilledViews(lf).size(), 10u);
  VirtualCameraParams p;
  p.width = p.height = 256;
  p.eye = lf.slab().uv.center();
  p.look_at = Vec3(370, 165, -300 + 40);  // the globe
  p.focal_length_mm = 300;
  const VirtualCamera camera(p);
  const double truth = TrueFocusDistance(camera, 128, 128);
  const FocusProbe probe = ProbeFocusDistance(lf, camera, 128, 128);
  ASSERT_TRUE(probe.found);
  EXPECT_NEAR(probe.focus_distance_mm, truth, 0.02 * truth);
  EXPECT_LE(probe.cameras, 90);  // the 10 filled are not compared
  EXPECT_GT(probe.cameras, 40);
}

TEST(FocusProbe, SaysWhenNoCameraSeesThePixel) {
  // A small array will do: no camera is asked (under the sanitizers this test runs without the
  // one above, and simulating its light field would take most of a quarter of a minute).
  SimulateLightFieldOptions o;
  o.rows = o.cols = 4;
  o.n_s = 40;
  o.n_t = 36;
  o.supersampling = 1;
  const LightField lf = SimulateLightField(PaperScene(), o);
  VirtualCameraParams p;
  p.width = p.height = 64;
  p.eye = lf.slab().uv.center();
  p.look_at = p.eye + Vec3(0, 0, 1000);  // away from the scene, the st-plane behind the eye
  const FocusProbe probe = ProbeFocusDistance(lf, VirtualCamera(p), 32, 32);
  EXPECT_FALSE(probe.found);
}

}  // namespace
}  // namespace lfcam
