#include "lfcam/render/rig_camera.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lfcam/core/error.h"

namespace lfcam {

VirtualCameraParams RigCameraParams(const LightField& lf, double row, double col) {
  const LightFieldDims& d = lf.dims();
  if (!lf.has_view_cameras())
    throw Error(
        "the light field records no camera for its views (it was simulated, or made by an lfcam "
        "before format version 3): import or build it again to render as one of its cameras");
  if (!std::isfinite(row) || !std::isfinite(col) || row < 0 || col < 0 || row > d.rows - 1 ||
      col > d.cols - 1)
    throw Error(
        fmt::format("camera ({}, {}) lies outside the {}x{} grid (rows 0 to {}, columns "
                    "0 to {}, row 0 at the bottom)",
                    row, col, d.rows, d.cols, d.rows - 1, d.cols - 1));
  const int r0 = std::min(int(std::floor(row)), d.rows - 1);
  const int c0 = std::min(int(std::floor(col)), d.cols - 1);
  const int r1 = std::min(r0 + 1, d.rows - 1), c1 = std::min(c0 + 1, d.cols - 1);
  const double fr = row - r0, fc = col - c0;
  auto pose = [&](int r, int c) -> const ViewPose& {
    return lf.measured_poses()[std::size_t(r) * d.cols + c];
  };
  Vec3 center = Vec3::Zero();
  Vec2 principal = Vec2::Zero();
  for (const auto& [r, c, w] :
       {std::tuple{r0, c0, (1 - fr) * (1 - fc)}, std::tuple{r0, c1, (1 - fr) * fc},
        std::tuple{r1, c0, fr * (1 - fc)}, std::tuple{r1, c1, fr * fc}}) {
    center += w * pose(r, c).center;
    principal += w * Vec2(pose(r, c).intrinsics->cx, pose(r, c).intrinsics->cy);
  }
  const ViewPose& nearest = pose(int(std::lround(row)), int(std::lround(col)));
  const CameraIntrinsics& k = *nearest.intrinsics;

  VirtualCameraParams p;
  p.width = k.width;
  p.height = k.height;
  p.eye = center;
  const Vec3 forward = nearest.orientation.col(2), down = nearest.orientation.col(1);
  const double focus = std::max(lf.slab().separation_mm(), 1e-6);
  p.look_at = center + focus * forward;
  p.up = -down;
  p.breathing = false;
  // Film 56 mm across W pixels at distance f: f / 56 = fx / W.
  p.focal_length_mm = kFilmSizeMm * k.fx / k.width;
  p.focus_distance_mm = focus;
  p.aperture_mm = 0;
  // OpenCV's principal point (pixel centres at integers, y down) -> the film's offset from its
  // centre (pixel centres at half integers, y up).
  p.principal_offset_px = {principal.x() + 0.5 - 0.5 * k.width,
                           0.5 * k.height - principal.y() - 0.5};
  p.lens_length_scale = LensLengthScale(lf);
  return p;
}

double LensLengthScale(const LightField& lf) {
  if (WorldLengthUnit(lf.metadata()) == "mm") return 1.0;
  const double pitch = lf.slab().uv.pitch_mm;  // in the light field's units
  return pitch > 0 && std::isfinite(pitch) ? ArrayPlane{}.pitch_mm / pitch : 1.0;
}

}  // namespace lfcam
