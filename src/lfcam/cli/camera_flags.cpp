#include "lfcam/cli/camera_flags.h"

#include <fmt/format.h>

#include <cmath>

#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"
#include "lfcam/render/lens_sampling.h"

namespace lfcam::cli {

void CameraFlags::AddTo(CLI::App& c) {
  c.add_option(
       "--size", size,
       fmt::format("Image size in pixels: N (square) or WxH, at most {} a side", kMaxImageSide))
      ->capture_default_str();
  c.add_option("--eye", eye, "Camera position e_c, X,Y,Z in world mm (default: array centre)");
  c.add_option("--look-at", look_at,
               "Point looked at, X,Y,Z in world mm (default: straight ahead, along -n_ca)");
  c.add_option("--up", up, "Up direction X,Y,Z (default: v_ca)");
  c.add_option("--focal-length", focal_length_mm, "Focal length f in mm (film is 56 mm)")
      ->capture_default_str();
  c.add_option("--focus-distance", focus_distance_mm,
               "Focus distance d_o in mm, from the lens; must exceed f")
      ->capture_default_str();
  c.add_option("--aperture", aperture_mm, "Aperture diameter d_l in mm (0 = pinhole)")
      ->capture_default_str();
  c.add_option(
       "--lens-rate", lens_rate,
       fmt::format("Lens sampling rate gamma_ls: n_ls = gamma (d_l/2)^2 / 210 rays a pixel, "
                   "at most {} (4 to 9 looks good)",
                   kMaxLensSamples))
      ->capture_default_str();
  c.add_flag("--no-breathing", no_breathing,
             "Keep the film at f (fixed field of view) and focus with f_e = f d_o / (f + d_o)");
}

void CameraFlags::Validate() const {
  const std::pair<int, int> image = ParseSize("--size", size, kMaxImageSide);
  // The linear image, its hit mask and their encoded copies: about 25 bytes a pixel.
  FlagValue("--size", [&] {
    RequireMemory(25.0 * image.first * image.second,
                  fmt::format("a {}x{} image", image.first, image.second));
  });
  if (!eye.empty()) ParseVec3("--eye", eye);
  if (!look_at.empty()) ParseVec3("--look-at", look_at);
  if (!up.empty()) ParseVec3("--up", up);
  if (!(focal_length_mm > 0) || !std::isfinite(focal_length_mm))
    throw UsageError(
        fmt::format("--focal-length: {} must be a positive number of mm", focal_length_mm));
  if (!(focus_distance_mm > focal_length_mm) || !std::isfinite(focus_distance_mm))
    throw UsageError(fmt::format("--focus-distance: {} mm must exceed the focal length ({} mm)",
                                 focus_distance_mm, focal_length_mm));
  if (!(aperture_mm >= 0) || !std::isfinite(aperture_mm))
    throw UsageError(
        fmt::format("--aperture: {} must be 0 (pinhole) or a positive number of mm", aperture_mm));
  if (!(lens_rate > 0) || !std::isfinite(lens_rate))
    throw UsageError(fmt::format("--lens-rate: {} must be positive", lens_rate));
  if (aperture_mm > 0) {
    try {
      LensSampleCount(lens_rate, aperture_mm);
    } catch (const Error& e) {
      throw UsageError(fmt::format("--lens-rate/--aperture: {}", e.what()));
    }
  }
}

VirtualCameraParams CameraFlags::Resolve(const ArrayPlane& array) const {
  VirtualCameraParams p;
  std::tie(p.width, p.height) = ParseSize("--size", size, kMaxImageSide);
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

VirtualCamera CameraFlags::MakeCamera(const ArrayPlane& array) const {
  Validate();
  try {
    return VirtualCamera(Resolve(array));
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(fmt::format("camera flags (--eye, --look-at, --up): {}", e.what()));
  }
}

}  // namespace lfcam::cli
