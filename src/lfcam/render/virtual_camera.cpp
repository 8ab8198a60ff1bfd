#include "lfcam/render/virtual_camera.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lfcam/core/error.h"
#include "lfcam/render/lens_sampling.h"

namespace lfcam {

double ThinLensImageDistance(double f, double d_o) { return f * d_o / (d_o - f); }
double EffectiveFocalLength(double f, double d_o) { return f * d_o / (f + d_o); }
double BreathingFieldOfView(double f, double d_o) {
  return 2.0 * std::atan(kFilmSizeMm * (d_o - f) / (2.0 * d_o * f));
}
double FixedFieldOfView(double f) { return 2.0 * std::atan(kFilmSizeMm / (2.0 * f)); }

VirtualCamera::VirtualCamera(const VirtualCameraParams& p) : params_(p) {
  if (p.width < 1 || p.height < 1 || p.width > 16384 || p.height > 16384)
    throw Error(fmt::format("image size {}x{} must be between 1 and 16384", p.width, p.height));
  if (!(p.focal_length_mm > 0) || !std::isfinite(p.focal_length_mm))
    throw Error(fmt::format("focal length {} mm must be positive", p.focal_length_mm));
  if (p.breathing &&
      (!(p.focus_distance_mm > p.focal_length_mm) || !std::isfinite(p.focus_distance_mm)))
    throw Error(fmt::format("focus distance {} mm must exceed the focal length {} mm",
                            p.focus_distance_mm, p.focal_length_mm));
  if (!(p.focus_distance_mm > 0) || !std::isfinite(p.focus_distance_mm))
    throw Error(fmt::format("focus distance {} mm must be positive", p.focus_distance_mm));
  if (!p.principal_offset_px.allFinite() ||
      p.principal_offset_px.cwiseAbs().maxCoeff() > 4.0 * std::max(p.width, p.height))
    throw Error(fmt::format("principal offset ({}, {}) px is not finite or lies far off the film",
                            p.principal_offset_px.x(), p.principal_offset_px.y()));
  if (!(p.aperture_mm >= 0) || !std::isfinite(p.aperture_mm))
    throw Error(fmt::format("aperture {} mm must be zero (pinhole) or positive", p.aperture_mm));
  if (!(p.lens_rate > 0) || !std::isfinite(p.lens_rate))
    throw Error(fmt::format("lens sampling rate {} must be positive", p.lens_rate));
  if (!p.eye.allFinite() || !p.look_at.allFinite() || !p.up.allFinite())
    throw Error("eye, look-at and up must be finite");
  const Vec3 back = p.eye - p.look_at;
  if (back.norm() < 1e-9) throw Error("eye and look-at coincide");
  n_c_ = back.normalized();
  const Vec3 right = p.up.cross(n_c_);
  if (right.norm() < 1e-9 * p.up.norm() || p.up.norm() < 1e-12)
    throw Error("up vector is zero or parallel to the viewing direction");
  u_c_ = right.normalized();
  v_c_ = n_c_.cross(u_c_);
  e_c_ = p.eye;

  if (p.breathing) {
    film_distance_ = ThinLensImageDistance(p.focal_length_mm, p.focus_distance_mm);
    lens_focal_ = p.focal_length_mm;
  } else {
    film_distance_ = p.focal_length_mm;
    lens_focal_ = EffectiveFocalLength(p.focal_length_mm, p.focus_distance_mm);
  }
  tan_half_x_ = 0.5 * kFilmSizeMm / film_distance_;
  tan_half_y_ = tan_half_x_ * p.height / p.width;
  lens_samples_ =
      is_pinhole()
          ? std::vector<Vec2>{Vec2::Zero()}
          : UnitDiskSamples(LensSampleCount(p.lens_rate, p.aperture_mm * p.lens_length_scale));
}

VirtualCameraParams WithFrameSize(const VirtualCameraParams& p, int width, int height) {
  VirtualCameraParams q = p;
  q.width = width;
  q.height = height;
  // A pixel spans the film's width over the frame's width, across and up alike.
  q.principal_offset_px = p.principal_offset_px * (double(width) / std::max(p.width, 1));
  return q;
}

double MinFocusDistance(const VirtualCameraParams& p) {
  return p.breathing ? 1.05 * p.focal_length_mm : 1e-3;
}

VirtualCamera VirtualCamera::WithLensSampleRange(int begin, int end) const {
  VirtualCamera part = *this;
  const int n = int(lens_samples_.size());
  begin = std::clamp(begin, 0, n);
  end = std::clamp(end, begin, n);
  part.lens_samples_.assign(lens_samples_.begin() + begin, lens_samples_.begin() + end);
  return part;
}

}  // namespace lfcam
