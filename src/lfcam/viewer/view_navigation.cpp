#include "lfcam/viewer/view_navigation.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "lfcam/core/error.h"
#include "lfcam/render/rig_camera.h"

namespace lfcam {
namespace {

// The camera's frame as VirtualCamera computes it.
struct Frame {
  Vec3 forward, right, up;
};

Frame FrameOf(const VirtualCameraParams& p) {
  const VirtualCamera camera(p);
  return {-camera.n_c(), camera.u_c(), camera.v_c()};
}

double LookDistance(const VirtualCameraParams& p) {
  return std::max((p.look_at - p.eye).norm(), 1.0);
}

}  // namespace

VirtualCameraParams Orbit(const VirtualCameraParams& p, double yaw, double pitch) {
  const Frame f = FrameOf(p);
  const Vec3 pivot = p.eye + p.focus_distance_mm * f.forward;
  const Eigen::AngleAxisd turn_yaw(-yaw, f.up);
  const Vec3 right = turn_yaw * f.right;
  const Eigen::AngleAxisd turn_pitch(pitch, right);
  const Eigen::Matrix3d rotation = (turn_pitch * turn_yaw).toRotationMatrix();
  VirtualCameraParams q = p;
  const Vec3 forward = rotation * f.forward;
  const Vec3 up = rotation * f.up;
  q.eye = pivot - p.focus_distance_mm * forward;
  q.look_at = q.eye + LookDistance(p) * forward;
  q.up = up;
  return q;
}

VirtualCameraParams Move(const VirtualCameraParams& p, double right_mm, double up_mm,
                         double forward_mm) {
  const Frame f = FrameOf(p);
  const Vec3 step = right_mm * f.right + up_mm * f.up + forward_mm * f.forward;
  VirtualCameraParams q = p;
  q.eye += step;
  q.look_at += step;
  return q;
}

double MmPerPixelAtFocus(const VirtualCameraParams& p) {
  const VirtualCamera camera(p);
  return p.focus_distance_mm * 2.0 * std::tan(0.5 * camera.field_of_view_rad()) / p.width;
}

VirtualCameraParams ResetToArrayCentre(const VirtualCameraParams& p, const ArrayPlane& array) {
  VirtualCameraParams q = p;
  q.eye = array.center();
  q.look_at = q.eye - 1000.0 * array.n_ca;
  q.up = array.v_ca;
  return q;
}

VirtualCameraParams AsRigCamera(const VirtualCameraParams& p, const LightField& lf, double row,
                                double col) {
  if (!lf.has_view_cameras())
    throw Error("this light field does not record the cameras that took its views");
  const auto& d = lf.dims();
  if (!(row >= 0 && row <= d.rows - 1 && col >= 0 && col <= d.cols - 1))
    throw Error(fmt::format("camera ({}, {}) is outside the {}x{} grid", row, col, d.rows, d.cols));
  VirtualCameraParams q = WithFrameSize(RigCameraParams(lf, row, col), p.width, p.height);
  q.lens_rate = p.lens_rate;
  return q;
}

VirtualCameraParams StartingView(const LightField& lf, int width, int height) {
  if (lf.has_view_cameras()) {
    const auto& d = lf.dims();
    const VirtualCameraParams rig = RigCameraParams(lf, 0.5 * (d.rows - 1), 0.5 * (d.cols - 1));
    return WithFrameSize(rig, width, height);
  }
  VirtualCameraParams p;
  p.width = width;
  p.height = height;
  p = ResetToArrayCentre(p, lf.slab().uv);
  p.focal_length_mm = 500;
  p.focus_distance_mm = 4000;
  return p;
}

VirtualCameraParams ScaleFocusDistance(const VirtualCameraParams& p, double factor) {
  VirtualCameraParams q = p;
  q.focus_distance_mm = std::max(p.focus_distance_mm * factor, MinFocusDistance(p));
  return q;
}

VirtualCameraParams ScaleFocalLength(const VirtualCameraParams& p, double factor) {
  VirtualCameraParams q = p;
  q.focal_length_mm = p.breathing
                          ? std::clamp(p.focal_length_mm * factor, 10.0, p.focus_distance_mm / 1.05)
                          : std::max(p.focal_length_mm * factor, 10.0);
  return q;
}

}  // namespace lfcam
