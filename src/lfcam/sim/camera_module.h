#pragma once
// The simulated Raspberry Pi camera module v1.3 (OmniVision OV5647: 2592 x 1944 pixels of
// 1.4 um, a 3.60 mm f/2.9 lens) and the defects a real array of them has: mounting error, spread
// of the intrinsics, lens distortion, the lens's blur, vignetting, exposure and white-balance
// spread, sensor noise.
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "lfcam/core/camera_model.h"
#include "lfcam/core/slab.h"
#include "lfcam/sim/shapes.h"

namespace lfcam {

inline constexpr int kPiCameraWidth = 2592;
inline constexpr int kPiCameraHeight = 1944;
inline constexpr double kPiCameraFocalMm = 3.60;
inline constexpr double kPiCameraPixelUm = 1.4;  // at full resolution
// The lens's point spread as a Gaussian's sigma on the sensor: diffraction at f/2.9 in green light
// alone is about 0.42 * 0.55 um * 2.9 = 0.67 um, and a moulded 3.6 mm lens adds its aberrations.
// Realistic modules draw theirs within +-kPiLensBlurSpreadUm of this.
inline constexpr double kPiLensBlurUm = 0.8;
inline constexpr double kPiLensBlurSpreadUm = 0.15;
inline constexpr double kMaxLensBlurUm = 20.0;  // what a simulated lens may be given

// A point spread of `um` on the sensor in pixels of a sensor read at `width` pixels across (the
// full 2592 binned or scaled: a pixel there is 2592 / width full-size pixels wide).
inline double LensBlurPx(double um, int width) {
  return um * (double(width) / kPiCameraWidth) / kPiCameraPixelUm;
}

// The nominal module at a sensor resolution of width x height (binned or scaled from the full
// 2592 x 1944; the field of view stays 53.5 x 41.4 degrees): no distortion, centred.
CameraIntrinsics NominalPiCamera(int width, int height);

// A module's photometric response: what it records for linear radiance L at pixel x is
//   gain[c] * L * (1 + vignetting[0] rho^2 + vignetting[1] rho^4),
// rho the distance from the image centre over the half-diagonal.
struct ModulePhotometry {
  Vec3 gain = Vec3::Ones();
  double vignetting[2] = {0.0, 0.0};
  double falloff(double rho2) const { return 1 + rho2 * (vignetting[0] + rho2 * vignetting[1]); }
};

struct SimulatedModule {
  int row = 0, col = 0;
  CameraIntrinsics intrinsics;
  Rigid3 world_from_camera;
  ModulePhotometry photometry;
  // The lens's blur: the sigma, in the module's pixels, of the Gaussian point spread each pixel's
  // footprint is spread by (0: a perfect lens).
  double lens_blur_px = 0.0;
};

enum class ModuleDefects { kNone, kRealistic };

// One module per grid position of `array`, looking along -n_ca. kRealistic draws, from `seed`:
// a centre within +-1 mm and a rotation within 1 degree of the ideal mount; focal lengths within
// +-2%; a principal point within +-20 px (scaled to the sensor); Brown-Conrady distortion of a
// 3.6 mm wide-angle lens; the lens's blur (kPiLensBlurUm within +-kPiLensBlurSpreadUm, drawn
// from a stream of its own, so that the rest of a rig is what it was before modules had one);
// vignetting; gain within +-15% and white balance within +-8%.
std::vector<SimulatedModule> MakeModules(const ArrayPlane& array, int width, int height,
                                         ModuleDefects defects, std::uint64_t seed);

// A pixel's footprint: the change of its centre ray's direction one pixel right (`dx`) and down
// (`dy`), and the lens's blur, which spreads the footprint by a Gaussian of sigma `blur_px`
// pixels.
struct PixelFootprint {
  Vec3 dx = Vec3::Zero(), dy = Vec3::Zero();
  double blur_px = 0.0;
};

// What a pixel sees: the linear radiance over the footprint of the pixel whose centre ray is
// `ray` (unit direction). `behind`, when not null, is what the pixel would see were the nearest
// thing not there (a scene rendered once and shared by every board shot of a module).
using PixelRadiance =
    std::function<Vec3(const Ray& ray, const PixelFootprint& footprint, const Vec3* behind)>;

struct ExposureOptions {
  bool noise = true;          // photon shot noise and read noise (off: an ideal sensor)
  double full_well = 4000.0;  // electrons at radiance 1 after gain: sets the shot noise
  double read_noise = 3.0;    // electrons, RMS
  std::uint64_t noise_seed = 1;
};

// Each pixel centre's viewing direction in the world frame (unit, CV_32FC3), distortion undone:
// computed once per module and shared by all its shots.
cv::Mat ModuleRayDirections(const SimulatedModule& module);

// For each image row, the columns [begin, end) where a radiance may differ from what stands
// behind it (begin >= end: none). A shot that changes only part of the image (a board) renders
// only there.
using PixelRuns = std::vector<cv::Vec2i>;

// The radiance each pixel sees, linear (CV_32FC3), without photometry or noise. `directions` is
// ModuleRayDirections(module); rows are rendered in parallel. With `behind` (CV_32FC3, the
// module's size), each pixel's value there is passed on to `radiance`; with `runs` too, pixels
// outside them take `behind` as it is and `radiance` is not called for them.
cv::Mat RenderRadiance(const SimulatedModule& module, const cv::Mat& directions,
                       const PixelRadiance& radiance, const cv::Mat* behind = nullptr,
                       const PixelRuns* runs = nullptr);

// The pixels whose footprints may meet any of `spheres` (world mm): per row, the run from the
// first such pixel to the last (empty runs where none). Conservative: a footprint is taken one
// and a half pixels wide.
PixelRuns SphereFootprintRuns(const SimulatedModule& module, const cv::Mat& directions,
                              const std::vector<BoundingSphere>& spheres);

// What the sensor records of `radiance` (CV_32FC3 linear, the module's size): the module's
// photometry, shot and read noise, 8-bit sRGB RGB (CV_8UC3, row 0 at the top). Rows in parallel;
// the noise is the same whatever the threads (one stream per row, from options.noise_seed).
cv::Mat ExposeRadiance(const SimulatedModule& module, const cv::Mat& radiance,
                       const ExposureOptions& options);

// RenderRadiance, then ExposeRadiance.
cv::Mat ExposeModule(const SimulatedModule& module, const cv::Mat& directions,
                     const PixelRadiance& radiance, const ExposureOptions& options,
                     const cv::Mat* behind = nullptr);

}  // namespace lfcam
