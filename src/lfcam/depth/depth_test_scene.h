#pragma once
// Tests only: a small scene whose depths are easy to state, and its light field. A textured wall
// 5 m from the array (D = 5000 mm) behind a textured plate at 3.2 m (D = 3200 mm) that hides
// part of it, in front of the `paper` scene's rig (array at z = 3600, view window at z = 0), seen
// by a 7 x 7 grid of 240 x 220 st samples. `turn_deg` turns the view window (the st-plane) about
// the vertical: a slab whose planes are not parallel.
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam::testing {

// The `paper` scene's rig with nothing in it but a textured wall 5 m from the array: the
// background of the tests' own scenes.
inline Scene WallScene(const std::string& name) {
  Scene scene = MakePaperScene();
  scene.name = name;
  scene.objects.clear();
  scene.Add("wall",
            std::make_shared<RectangleShape>(Vec3(300, 275, -1400), Vec3::UnitX(), Vec3::UnitY(),
                                             1500, 1500),
            Texture{Pattern::kNoise, {0.1, 0.15, 0.3}, {0.9, 0.8, 0.6}, 20, 3});
  return scene;
}

inline Scene TwoPlaneScene(double turn_deg = 0.0) {
  Scene scene = WallScene("two planes");
  const double a = turn_deg * std::numbers::pi / 180.0;
  scene.rig.board.x_axis = Vec3(std::cos(a), 0.0, -std::sin(a));
  scene.Add(
      "plate",
      std::make_shared<RectangleShape>(Vec3(330, 250, 400), Vec3::UnitX(), Vec3::UnitY(), 110, 90),
      Texture{Pattern::kNoise, {0.6, 0.1, 0.05}, {0.95, 0.9, 0.3}, 12, 9});
  return scene;
}

// `off_plane_mm` > 0: each camera moved along the array's normal by its own amount, at most that
// (a calibrated array's cameras lie a millimetre or two off one plane; recorded as measured).
inline LightField TwoPlaneLightField(const Scene& scene, double off_plane_mm = 0.0) {
  SimulateLightFieldOptions o;
  o.rows = o.cols = 7;
  o.n_s = 240;
  o.n_t = 220;
  o.supersampling = 1;
  if (off_plane_mm > 0) {
    Slab slab = scene.IdealSlab(o.st_domain);
    slab.uv = ResizeArray(slab.uv, o.rows, o.cols);
    for (int r = 0; r < o.rows; ++r)
      for (int c = 0; c < o.cols; ++c)
        o.camera_centers.push_back(slab.uv.camera_center(r, c) +
                                   slab.uv.n_ca *
                                       (off_plane_mm * std::sin(1.7 * (r * o.cols + c) + 0.3)));
  }
  return SimulateLightField(scene, o);
}

// n planes from in front of the plate (2.8 m) to beyond the wall (6 m), uniformly in 1/D: the
// inverse depths a sweep of this scene takes.
inline std::vector<double> SweepPlanes(int n) {
  std::vector<double> q;
  for (int i = 0; i < n; ++i) q.push_back(1.0 / 2800 + (1.0 / 6000 - 1.0 / 2800) * i / (n - 1));
  return q;
}

}  // namespace lfcam::testing
