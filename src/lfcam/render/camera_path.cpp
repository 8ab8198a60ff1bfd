#include "lfcam/render/camera_path.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

template <typename T>
T Lerp(const T& a, const T& b, double t) {
  return a + (b - a) * t;
}

// The Catmull-Rom spline through points[i] at t = 0 and points[i + 1] at t = 1; the missing
// neighbours at the ends are reflected, so the end tangents are the end legs.
Vec3 CatmullRom(const std::vector<Vec3>& points, std::size_t i, double t) {
  const std::size_t n = points.size();
  const Vec3& p1 = points[i];
  const Vec3& p2 = points[i + 1];
  const Vec3 p0 = i > 0 ? points[i - 1] : Vec3(2.0 * p1 - p2);
  const Vec3 p3 = i + 2 < n ? points[i + 2] : Vec3(2.0 * p2 - p1);
  const Vec3 m1 = 0.5 * (p2 - p0), m2 = 0.5 * (p3 - p1);
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * p1 + (t3 - 2 * t2 + t) * m1 + (-2 * t3 + 3 * t2) * p2 +
         (t3 - t2) * m2;
}

}  // namespace

CameraPath CameraPath::Fixed(const VirtualCameraParams& camera) {
  CameraPath path;
  path.keys_ = {camera};
  return path;
}

CameraPath CameraPath::Sweep(const VirtualCameraParams& base, const CameraSweep& sweep) {
  CameraPath path = Fixed(base);
  path.sweep_ = sweep;
  return path;
}

CameraPath CameraPath::ThroughViews(const std::vector<VirtualCameraParams>& views,
                                    const std::vector<std::string>& names) {
  if (views.size() < 2) throw Error("a camera path needs at least two views");
  const auto name = [&](std::size_t i) {
    return i < names.size() ? names[i] : fmt::format("view {}", i + 1);
  };
  for (std::size_t i = 1; i < views.size(); ++i) {
    const VirtualCameraParams &first = views[0], &v = views[i];
    if (v.width != first.width || v.height != first.height)
      throw Error(
          fmt::format("{}: camera.width/height {}x{} differ from {}'s {}x{} (a video has "
                      "one frame size; --size sets it for every view)",
                      name(i), v.width, v.height, name(0), first.width, first.height));
    if (v.breathing != first.breathing)
      throw Error(
          fmt::format("{}: camera.breathing is {} and {}'s is {} (the film cannot both "
                      "move and stay along one path)",
                      name(i), v.breathing, name(0), first.breathing));
  }
  CameraPath path;
  path.keys_ = views;
  return path;
}

VirtualCameraParams CameraPath::At(double u) const {
  u = std::clamp(std::isfinite(u) ? u : 0.0, 0.0, 1.0);
  VirtualCameraParams p = keys_.front();
  if (keys_.size() >= 2) {
    const std::size_t legs = keys_.size() - 1;
    const std::size_t leg = std::min(legs - 1, std::size_t(u * double(legs)));
    const double t = u * double(legs) - double(leg);
    const VirtualCameraParams &a = keys_[leg], &b = keys_[leg + 1];
    std::vector<Vec3> eyes, targets;
    for (const auto& k : keys_) {
      eyes.push_back(k.eye);
      targets.push_back(k.look_at);
    }
    p = a;
    p.eye = CatmullRom(eyes, leg, t);
    p.look_at = CatmullRom(targets, leg, t);
    const Vec3 up = Lerp(a.up.normalized(), b.up.normalized(), t);
    p.up = up.norm() > 1e-9 ? Vec3(up.normalized()) : a.up;
    p.focal_length_mm = Lerp(a.focal_length_mm, b.focal_length_mm, t);
    p.focus_distance_mm = Lerp(a.focus_distance_mm, b.focus_distance_mm, t);
    p.aperture_mm = Lerp(a.aperture_mm, b.aperture_mm, t);
    p.lens_rate = Lerp(a.lens_rate, b.lens_rate, t);
    p.principal_offset_px = Lerp(a.principal_offset_px, b.principal_offset_px, t);
  }
  const CameraSweep& s = sweep_;
  if (s.eye) p.eye = Lerp(s.eye->first, s.eye->second, u);
  if (s.look_at) p.look_at = Lerp(s.look_at->first, s.look_at->second, u);
  if (s.focal_length_mm)
    p.focal_length_mm = Lerp(s.focal_length_mm->first, s.focal_length_mm->second, u);
  if (s.focus_distance_mm)
    p.focus_distance_mm = Lerp(s.focus_distance_mm->first, s.focus_distance_mm->second, u);
  if (s.aperture_mm) p.aperture_mm = Lerp(s.aperture_mm->first, s.aperture_mm->second, u);
  return p;
}

VirtualCameraParams CameraPath::AtFrame(int k, int frames) const {
  return At(frames > 1 ? double(k) / double(frames - 1) : 0.0);
}

}  // namespace lfcam
