#pragma once
// The paper's virtual camera (§6.1), set up once per frame and shared by every renderer (the
// light field renderers and the scene oracle), so that they all see the same rays.
//
// Frame (e_c; u_c, v_c, n_c), looking along -n_c as in OpenGL. Film 56 mm across (the width;
// the height is 56 * H / W). Focus distance d_o: in breathing mode the film sits at d_i with
// 1/d_i + 1/d_o = 1/f, so the field of view is 2 atan(56 (d_o - f) / (2 d_o f)); in
// non-breathing mode the film stays at f and the lens takes the effective focal length
// f_e = f d_o / (f + d_o), so the field of view stays 2 atan(56 / 2f) (and d_o need only be
// positive: the film does not move).
#include <vector>

#include "lfcam/core/geometry.h"

namespace lfcam {

struct VirtualCameraParams {
  int width = 1024;
  int height = 1024;
  Vec3 eye = Vec3::Zero();        // e_c, world mm
  Vec3 look_at = -Vec3::UnitZ();  // world mm
  Vec3 up = Vec3::UnitY();
  double focal_length_mm = 500.0;     // f
  double focus_distance_mm = 4000.0;  // d_o, from the lens along -n_c
  double aperture_mm = 0.0;           // d_l; 0 = pinhole
  double lens_rate = 4.0;             // gamma_ls
  bool breathing = true;
  // Where the optical axis meets the film, from the film's centre, in pixels (x right, y up): a
  // shifted sensor (an off-axis projection, as a rectified rig's cameras have). Zero: centred.
  Vec2 principal_offset_px = Vec2::Zero();
  // The mm one unit of length counts as when the lens samples are counted, n_ls = γ (s d_l / 2)²
  // / 210: 1 where lengths are mm; in a light field whose lengths are units of its cameras'
  // spacing, the paper's spacing, 28 mm, a unit (LensLengthScale, render/rig_camera.h), so that
  // each camera's cell is sampled as densely as the paper's.
  double lens_length_scale = 1.0;
};

inline constexpr double kFilmSizeMm = 56.0;

// The same camera with a frame of width x height pixels: the field of view across is the film's,
// and a principal offset (in pixels) scales with the frame's width (a pixel is film width / W).
VirtualCameraParams WithFrameSize(const VirtualCameraParams& p, int width, int height);
// The nearest focus distance the camera allows: beyond the focal length when the film breathes,
// anything in front of the lens otherwise.
double MinFocusDistance(const VirtualCameraParams& p);

double ThinLensImageDistance(double focal_length_mm, double focus_distance_mm);  // d_i
double EffectiveFocalLength(double focal_length_mm, double focus_distance_mm);   // f_e
double BreathingFieldOfView(double focal_length_mm, double focus_distance_mm);   // radians
double FixedFieldOfView(double focal_length_mm);                                 // radians

class VirtualCamera {
 public:
  explicit VirtualCamera(const VirtualCameraParams& params);  // throws lfcam::Error

  const VirtualCameraParams& params() const { return params_; }
  int width() const { return params_.width; }
  int height() const { return params_.height; }
  const Vec3& e_c() const { return e_c_; }
  const Vec3& u_c() const { return u_c_; }
  const Vec3& v_c() const { return v_c_; }
  const Vec3& n_c() const { return n_c_; }
  double film_distance_mm() const { return film_distance_; }                 // d_i or f
  double lens_focal_length_mm() const { return lens_focal_; }                // f or f_e
  double field_of_view_rad() const { return 2.0 * std::atan(tan_half_x_); }  // across the width
  bool is_pinhole() const { return params_.aperture_mm <= 0.0; }

  // Direction (not unit; its component along -n_c is 1) of the ray through the lens centre from
  // film position (x, y) in pixel units, bottom-left origin: pixel (i, j)'s centre is
  // (i + 0.5, j + 0.5). This is the paper's
  //   -n_c + tan(theta/2) ((2i+1)/N - 1) u_c + tan(theta/2) ((2j+1)/N - 1) v_c.
  // With a principal offset (ox, oy) the film is shifted: x - ox and y - oy take x's and y's place.
  Vec3 direction_through(double x, double y) const {
    return -n_c_ +
           (tan_half_x_ * (2.0 * (x - params_.principal_offset_px.x()) / params_.width - 1.0)) *
               u_c_ +
           (tan_half_y_ * (2.0 * (y - params_.principal_offset_px.y()) / params_.height - 1.0)) *
               v_c_;
  }
  Vec3 pixel_direction(int i, int j) const { return direction_through(i + 0.5, j + 0.5); }
  // p_o: where the central ray along `direction` meets the plane of focus.
  Vec3 focus_point(const Vec3& direction) const {
    return e_c_ + params_.focus_distance_mm * direction;
  }
  // The world point on the lens for a unit-disk sample.
  Vec3 lens_point(const Vec2& disk) const {
    const double r = 0.5 * params_.aperture_mm;
    return e_c_ + (r * disk.x()) * u_c_ + (r * disk.y()) * v_c_;
  }
  // The unit-disk lens samples (n_ls of them; one, the centre, for a pinhole).
  const std::vector<Vec2>& lens_samples() const { return lens_samples_; }
  // The same camera with only lens samples [begin, end) (clamped to the n_ls there are): what
  // the viewer renders a part at a time and accumulates (RenderResult::counts) into the frame
  // the whole set gives.
  VirtualCamera WithLensSampleRange(int begin, int end) const;
  // Image row (top-down, as stored) of pixel row j (bottom-up, as in the paper).
  int image_row(int j) const { return params_.height - 1 - j; }

 private:
  VirtualCameraParams params_;
  Vec3 e_c_, u_c_, v_c_, n_c_;
  double film_distance_ = 0, lens_focal_ = 0, tan_half_x_ = 0, tan_half_y_ = 0;
  std::vector<Vec2> lens_samples_;
};

}  // namespace lfcam
