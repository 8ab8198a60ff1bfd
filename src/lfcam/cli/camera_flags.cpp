#include "lfcam/cli/camera_flags.h"

#include "lfcam/cli/parse.h"

namespace lfcam::cli {

void CameraFlags::AddTo(CLI::App& c) {
  c.add_option("--size", size, "Image size in pixels: N (square) or WxH")->capture_default_str();
  c.add_option("--eye", eye, "Camera position e_c, X,Y,Z in world mm (default: array centre)");
  c.add_option("--look-at", look_at,
               "Point looked at, X,Y,Z in world mm (default: straight ahead, along -n_ca)");
  c.add_option("--up", up, "Up direction X,Y,Z (default: v_ca)");
  c.add_option("--focal-length", focal_length_mm, "Focal length f in mm (film is 56 mm)")
      ->capture_default_str();
  c.add_option("--focus-distance", focus_distance_mm, "Focus distance d_o in mm")
      ->capture_default_str();
  c.add_option("--aperture", aperture_mm, "Aperture diameter d_l in mm (0 = pinhole)")
      ->capture_default_str();
  c.add_option("--lens-rate", lens_rate, "Lens sampling rate gamma_ls (4 to 9 looks good)")
      ->capture_default_str();
  c.add_flag("--no-breathing", no_breathing,
             "Keep the film at f (fixed field of view) and focus with f_e = f d_o / (f + d_o)");
}

VirtualCameraParams CameraFlags::Resolve(const ArrayPlane& array) const {
  VirtualCameraParams p;
  std::tie(p.width, p.height) = ParseSize("--size", size);
  p.eye = eye.empty() ? array.center() : ParseVec3("--eye", eye);
  p.look_at = look_at.empty() ? Vec3(p.eye - 1000.0 * array.n_ca) : ParseVec3("--look-at", look_at);
  p.up = up.empty() ? array.v_ca : ParseVec3("--up", up);
  p.focal_length_mm = focal_length_mm;
  p.focus_distance_mm = focus_distance_mm;
  p.aperture_mm = aperture_mm;
  p.lens_rate = lens_rate;
  p.breathing = !no_breathing;
  return p;
}

}  // namespace lfcam::cli
