#pragma once
// Light fields and virtual cameras shared by the renderers' agreement tests (the vectorised CPU
// renderer against the scalar reference, the GL renderer against the CPU renderer): the paper's
// scene, small, and cameras that reach every path (pinhole and aperture, on and off the array's
// plane, turned and rolled, breathing on and off, rays leaving the domain).
#include <cmath>
#include <string>
#include <vector>

#include "lfcam/render/cpu_renderer.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam::render_test {

// A camera of the convergence tests (lens samples toward an integrator's limit): where it stands
// and looks, and its lens.
struct ConvergenceCamera {
  const char* name;
  Vec3 eye, look_at;
  double focal_length, focus_distance, aperture;
  bool breathing;
  VirtualCameraParams Params(int size) const {
    VirtualCameraParams p;
    p.width = p.height = size;
    p.eye = eye;
    p.look_at = look_at;
    p.focal_length_mm = focal_length;
    p.focus_distance_mm = focus_distance;
    p.aperture_mm = aperture;
    p.breathing = breathing;
    return p;
  }
};

// The paper scene on the paper's 10 x 10 grid, small: views of 156 x 144 samples over the
// paper's st domain, 8-bit sRGB, one ray a sample.
inline const LightField& GridPaperLightField() {
  static const LightField lf = [] {
    SimulateLightFieldOptions o;
    o.n_s = 156;
    o.n_t = 144;
    o.st_domain = StDomain{-1.2, -1.2, 1.2, 1.2};
    o.supersampling = 1;
    return SimulateLightField(MakePaperScene(), o);
  }();
  return lf;
}

// The paper scene, small: 6 x 7 cameras (rows x cols) of 96 x 88 samples, 8-bit sRGB, from
// cameras a little off the ideal grid (as a calibrated array's are).
inline const LightField& SmallPaperLightField() {
  static const LightField lf = [] {
    SimulateLightFieldOptions o;
    o.rows = 6;
    o.cols = 7;
    o.n_s = 96;
    o.n_t = 88;
    o.st_domain = StDomain{-1.2, -1.2, 1.2, 1.2};
    o.supersampling = 1;
    const Scene scene = MakePaperScene();
    LightField ideal = SimulateLightField(scene, o);
    for (int r = 0; r < o.rows; ++r)
      for (int c = 0; c < o.cols; ++c)
        o.camera_centers.push_back(ideal.camera_center(r, c) + Vec3(0.7 * std::sin(r + 2.0 * c),
                                                                    0.5 * std::cos(3.0 * r - c),
                                                                    0));
    return SimulateLightField(scene, o);
  }();
  return lf;
}

// The same samples on an st-plane turned a little against the array (0.03 degrees about its
// normal, 0.05 degrees out of the array's plane), as a calibrated light field's world board is:
// only nearly separable.
inline const LightField& TurnedStPlaneLightField() {
  static const LightField lf = [] {
    LightField turned = SmallPaperLightField();
    ViewWindow& st = turned.mutable_slab().st;
    const Mat3 turn = (Eigen::AngleAxisd(5e-4, Vec3::UnitZ()) *
                       Eigen::AngleAxisd(9e-4, Vec3(1, 1, 0).normalized()))
                          .toRotationMatrix();
    st.x_axis = turn * st.x_axis;
    st.y_axis = turn * st.y_axis;
    return turned;
  }();
  return lf;
}

struct Case {
  std::string name;
  VirtualCameraParams camera;
  Integrator integrator;
  Interpolation interpolation;
  std::string path;     // the fast path expected: "separable" or "rows"
  bool turned = false;  // on TurnedStPlaneLightField()
};

inline std::vector<Case> Cases() {
  const LightField& lf = SmallPaperLightField();
  const Vec3 centre = lf.slab().uv.center();
  VirtualCameraParams base;
  base.width = 61;  // not a multiple of any vector length
  base.height = 47;
  base.eye = centre;
  base.look_at = centre - Vec3(0, 0, 4000);
  base.focal_length_mm = 300;
  base.focus_distance_mm = 3900;
  base.lens_rate = 2;
  std::vector<Case> cases;
  // `cameras_path`, where given, is the cameras integrator's (lens samples take `path`).
  const auto add = [&](const std::string& name, VirtualCameraParams p, const std::string& path,
                       bool turned = false, const std::string& cameras_path = "") {
    for (const Integrator integrator : {Integrator::kLensSamples, Integrator::kCameras})
      for (const Interpolation interpolation :
           {Interpolation::kQuadrilinear, Interpolation::kFocalPlane}) {
        if (integrator == Integrator::kCameras && interpolation == Interpolation::kQuadrilinear)
          continue;  // the cameras integrator has one lookup
        const bool own = integrator == Integrator::kCameras && !cameras_path.empty();
        cases.push_back({name + " " + ToString(integrator) + " " + ToString(interpolation), p,
                         integrator, interpolation, own ? cameras_path : path, turned});
      }
  };
  VirtualCameraParams p = base;
  add("pinhole at the centre", p, "separable");
  p.aperture_mm = 90;
  add("aperture at the centre", p, "separable");
  p.breathing = false;
  p.eye = centre + Vec3(-40, 23, 0);
  p.look_at = p.eye - Vec3(0, 0, 1000);
  add("aperture elsewhere on the array, no breathing", p, "separable");
  // Wide enough that rays leave the st domain, and lens samples leave the array window.
  p = base;
  p.focal_length_mm = 60;
  p.aperture_mm = 120;
  p.eye = centre + Vec3(60, -50, 0);
  p.look_at = p.eye - Vec3(0, 0, 1000);
  add("wide, off-centre, past the edges", p, "separable");
  p = base;
  p.aperture_mm = 90;
  p.width = 300;  // wide enough that l crosses a sample row along a pixel row
  add("aperture at the centre, turned st-plane", p, "separable", true);
  p.focal_length_mm = 60;
  p.aperture_mm = 0;
  add("wide pinhole, turned st-plane", p, "separable", true);
  p = base;
  p.eye = centre + Vec3(30, -20, 700);
  p.aperture_mm = 70;
  // Turned a little (a quarter to a third of a degree), within the separable maps' tolerance.
  add("aperture in front of the array", p, "rows", false, "separable");
  // Off the array's plane but looking along its normal: the cameras integrator's maps stay
  // separable, each pixel with its own weights (wide, so that footprints leave the window).
  VirtualCameraParams q = p;
  q.look_at = q.eye - Vec3(0, 0, 1000);
  add("aperture in front of the array, looking along its normal", q, "rows", false, "separable");
  q.eye = centre + Vec3(-50, 35, -600);
  q.look_at = q.eye - Vec3(0, 0, 1000);
  q.focal_length_mm = 90;
  q.aperture_mm = 110;
  add("wide aperture behind the array, looking along its normal", q, "rows", false, "separable");
  q.breathing = false;
  add("the same on the turned st-plane", q, "rows", true, "separable");
  // Turned about the array's vertical axis (an orbit sideways), on the array's plane and in
  // front of it: l changes along the pixel rows, by more than a sample row across a vector.
  q = base;
  q.aperture_mm = 80;
  q.look_at = centre + Vec3(250, 0, -4000);
  add("aperture at the centre, turned about the vertical", q, "rows", false, "separable");
  q.eye = centre + Vec3(30, -20, 700);
  q.look_at = centre + Vec3(-400, -20, -3000);
  q.width = 300;
  add("aperture in front of the array, turned about the vertical", q, "rows", false, "separable");
  // Wide and turned far: l crosses several sample rows within a vector of pixels.
  q = base;
  q.focal_length_mm = 40;
  q.aperture_mm = 100;
  q.focus_distance_mm = 1500;
  q.look_at = centre + Vec3(2300, 0, -4000);
  add("wide, turned 30 degrees about the vertical", q, "rows", false, "separable");
  // Turned about both axes: not separable, and along a pixel row a camera's reads cross up to
  // eight sample rows (the cameras integrator's row kernel resamples them; beyond, gathers).
  q.look_at = centre + Vec3(1500, 400, -4000);
  add("wide, turned about both axes", q, "rows");
  // Turned up: k drifts with the pixel row, slowly, but past the tolerance over the pixel rows
  // that read one sample row (each resampled for every seven rows).
  q = base;
  q.width = 200;
  q.focal_length_mm = 600;
  q.aperture_mm = 60;
  q.eye = centre + Vec3(20, -10, -150);
  q.look_at = centre + Vec3(20, 400, -4000);
  add("turned up, in front of the array", q, "rows", false, "separable");
  p.look_at = centre + Vec3(250, 150, -3000);
  add("aperture in front of the array, turned", p, "rows", false, "separable");
  p.up = Vec3(std::sin(0.7), std::cos(0.7), 0);  // rolled 40 degrees: l runs along the rows
  add("aperture in front of the array, rolled", p, "rows");
  p.up = Vec3::UnitY();
  p.aperture_mm = 0;
  add("pinhole turned", p, "rows");
  p.breathing = false;
  p.focal_length_mm = 80;
  p.eye = centre + Vec3(0, 0, -500);
  add("pinhole behind the array, wide, no breathing", p, "rows");
  return cases;
}

// The cases, and for each of the cameras integrator's also its quadrilinear limit (the views
// prefiltered: on the GPU, or on the CPU kept every few samples).
inline std::vector<Case> WithQuadrilinearLimits(const std::vector<Case>& cases) {
  std::vector<Case> out;
  for (const Case& c : cases) {
    out.push_back(c);
    if (c.integrator != Integrator::kCameras) continue;
    Case limit = c;
    limit.integrator = Integrator::kCamerasQuadrilinear;
    limit.interpolation = Interpolation::kQuadrilinear;
    limit.name += " (its quadrilinear limit)";
    out.push_back(limit);
  }
  return out;
}

}  // namespace lfcam::render_test
