#include "lfcam/sim/camera_module.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>
#include <random>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"
#include "lfcam/sim/splitmix.h"

namespace lfcam {

CameraIntrinsics NominalPiCamera(int width, int height) {
  if (width < 8 || height < 8 || width > kMaxImageSide || height > kMaxImageSide)
    throw Error(
        fmt::format("sensor {}x{} is out of range (8..{} a side)", width, height, kMaxImageSide));
  CameraIntrinsics c;
  c.width = width;
  c.height = height;
  // The focal length in pixels scales with the sensor's width: the field of view is kept.
  const double full_focal_px = kPiCameraFocalMm / (kPiCameraPixelUm * 1e-3);
  c.fx = full_focal_px * width / kPiCameraWidth;
  c.fy = full_focal_px * height / kPiCameraHeight;
  c.cx = 0.5 * (width - 1);
  c.cy = 0.5 * (height - 1);
  return c;
}

std::vector<SimulatedModule> MakeModules(const ArrayPlane& array, int width, int height,
                                         ModuleDefects defects, std::uint64_t seed) {
  const CameraIntrinsics nominal = NominalPiCamera(width, height);
  const Mat3 ideal_rotation = WorldFromCameraRotation(array.u_ca, array.v_ca, array.n_ca);
  std::mt19937_64 rng(seed);
  auto uniform = [&rng](double center, double half_width) {
    return std::uniform_real_distribution<double>(center - half_width, center + half_width)(rng);
  };
  std::mt19937_64 lens_rng(seed ^ 0x5DEECE66D1E45B1Full);
  std::uniform_real_distribution<double> lens_blur_um(kPiLensBlurUm - kPiLensBlurSpreadUm,
                                                      kPiLensBlurUm + kPiLensBlurSpreadUm);
  const double degree = std::numbers::pi / 180.0;
  const double pixel_scale = double(width) / kPiCameraWidth;
  std::vector<SimulatedModule> modules;
  for (int row = 0; row < array.rows; ++row) {
    for (int col = 0; col < array.cols; ++col) {
      SimulatedModule m;
      m.row = row;
      m.col = col;
      m.intrinsics = nominal;
      m.world_from_camera = {ideal_rotation, array.camera_center(row, col)};
      if (defects == ModuleDefects::kRealistic) {
        // Mounting: the centre within +-1 mm along each array axis, the rotation within 1 degree
        // about each camera axis.
        // Each draw its own statement: C++ leaves the order of a call's arguments (and of an
        // overloaded operator's operands) to the compiler, and the rig must be the same
        // whichever compiles it. The order is the one GCC has always taken (last operand first),
        // so the simulated rigs, and the figures in docs/, are those measured before.
        const double along_n = uniform(0, 1.0), along_v = uniform(0, 1.0),
                     along_u = uniform(0, 1.0);
        m.world_from_camera.translation +=
            along_u * array.u_ca + along_v * array.v_ca + along_n * array.n_ca;
        const double tilt_z = uniform(0, degree), tilt_y = uniform(0, degree),
                     tilt_x = uniform(0, degree);
        const Vec3 tilt(tilt_x, tilt_y, tilt_z);
        m.world_from_camera.rotation = ideal_rotation * RotationFromAngleAxis(tilt);
        CameraIntrinsics& c = m.intrinsics;
        const double focal_scale = uniform(1.0, 0.02);
        c.fx *= focal_scale;
        c.fy *= focal_scale * uniform(1.0, 0.002);  // square pixels, nearly
        c.cx += uniform(0, 20.0) * pixel_scale;
        c.cy += uniform(0, 20.0) * pixel_scale;
        // A 3.6 mm wide-angle lens: mild barrel distortion in the middle, less at the corners.
        c.distortion = {uniform(0.10, 0.03), uniform(-0.22, 0.05), uniform(0, 0.0015),
                        uniform(0, 0.0015), uniform(0.07, 0.03)};
        const double exposure = uniform(1.0, 0.15);
        const double blue = uniform(1.0, 0.08), red = uniform(1.0, 0.08);
        m.photometry.gain = exposure * Vec3(red, 1.0, blue);
        m.photometry.vignetting[0] = uniform(-0.30, 0.05);
        m.photometry.vignetting[1] = uniform(-0.05, 0.03);
        m.lens_blur_px = LensBlurPx(lens_blur_um(lens_rng), width);
      }
      modules.push_back(m);
    }
  }
  return modules;
}

cv::Mat ModuleRayDirections(const SimulatedModule& module) {
  const CameraIntrinsics& c = module.intrinsics;
  const Mat3& rotation = module.world_from_camera.rotation;
  cv::Mat directions(c.height, c.width, CV_32FC3);
  tbb::parallel_for(tbb::blocked_range<int>(0, c.height, 16), [&](const auto& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      auto* out = directions.ptr<cv::Vec3f>(y);
      for (int x = 0; x < c.width; ++x) {
        const auto d = c.Unproject(Vec2(x, y));
        if (!d)
          throw Error(fmt::format("camera {},{}: its distortion cannot be undone at pixel ({}, {})",
                                  module.row, module.col, x, y));
        const Vec3 w = (rotation * *d).normalized();
        out[x] = cv::Vec3f(float(w.x()), float(w.y()), float(w.z()));
      }
    }
  });
  return directions;
}

namespace {

Vec3 ToVec3(const cv::Vec3f& v) { return {v[0], v[1], v[2]}; }

// Sensor noise needs many Gaussian numbers fast, reproducibly: splitmix64, and the sum of four
// 16-bit uniforms (Irwin-Hall, scaled to unit variance): within 1% of a Gaussian's spread, with
// tails cut at 3.5 sigma, which is all that shot and read noise need.
class NoiseSource {
 public:
  explicit NoiseSource(std::uint64_t seed) : state_(seed) {}
  float Gaussian() {
    const std::uint64_t z = SplitMixNext(state_);
    const auto sum = float(std::uint32_t(z & 0xFFFF) + std::uint32_t((z >> 16) & 0xFFFF) +
                           std::uint32_t((z >> 32) & 0xFFFF) + std::uint32_t(z >> 48));
    // Four uniforms on [0, 1): mean 2, variance 1/3.
    return (sum * (1.0f / 65536.0f) - 2.0f) * 1.7320508f;
  }

 private:
  std::uint64_t state_;
};

void RequireModuleImage(const SimulatedModule& module, const cv::Mat& image, const char* what) {
  const CameraIntrinsics& c = module.intrinsics;
  if (image.rows != c.height || image.cols != c.width || image.type() != CV_32FC3)
    throw Error(fmt::format("the {} does not match the module", what));
}

}  // namespace

cv::Mat RenderRadiance(const SimulatedModule& module, const cv::Mat& directions,
                       const PixelRadiance& radiance, const cv::Mat* behind,
                       const PixelRuns* runs) {
  const CameraIntrinsics& c = module.intrinsics;
  RequireModuleImage(module, directions, "direction map");
  if (behind) RequireModuleImage(module, *behind, "background image");
  if (runs && (!behind || int(runs->size()) != c.height))
    throw Error("pixel runs need a background image and one run per row");
  cv::Mat out = behind ? behind->clone() : cv::Mat(c.height, c.width, CV_32FC3);
  const Vec3 origin = module.world_from_camera.translation;
  tbb::parallel_for(tbb::blocked_range<int>(0, c.height, 8), [&](const auto& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      const auto* d = directions.ptr<cv::Vec3f>(y);
      const auto* d_down = directions.ptr<cv::Vec3f>(y + 1 < c.height ? y + 1 : y - 1);
      const double dy_sign = y + 1 < c.height ? 1.0 : -1.0;
      auto* o = out.ptr<cv::Vec3f>(y);
      const int begin = runs ? std::max(0, (*runs)[std::size_t(y)][0]) : 0;
      const int end = runs ? std::min(c.width, (*runs)[std::size_t(y)][1]) : c.width;
      for (int x = begin; x < end; ++x) {
        // The ray through the pixel's centre, and its change one pixel right and down.
        const Vec3 dir = ToVec3(d[x]);
        const int xn = x + 1 < c.width ? x + 1 : x - 1;
        const PixelFootprint footprint{(ToVec3(d[xn]) - dir) * (x + 1 < c.width ? 1.0 : -1.0),
                                       (ToVec3(d_down[x]) - dir) * dy_sign, module.lens_blur_px};
        Vec3 back;
        if (behind) back = ToVec3(o[x]);
        const Vec3 v = radiance(Ray{origin, dir}, footprint, behind ? &back : nullptr);
        o[x] = cv::Vec3f(float(v.x()), float(v.y()), float(v.z()));
      }
    }
  });
  return out;
}

PixelRuns SphereFootprintRuns(const SimulatedModule& module, const cv::Mat& directions,
                              const std::vector<BoundingSphere>& spheres) {
  RequireModuleImage(module, directions, "direction map");
  const int width = directions.cols, height = directions.rows;
  const Vec3 origin = module.world_from_camera.translation;
  PixelRuns runs(std::size_t(height), cv::Vec2i(0, 0));
  if (spheres.empty()) return runs;
  tbb::parallel_for(0, height, [&](int y) {
    const auto* d = directions.ptr<cv::Vec3f>(y);
    const auto* d_down = directions.ptr<cv::Vec3f>(y + 1 < height ? y + 1 : y - 1);
    int begin = width, end = 0;
    for (int x = 0; x < width; ++x) {
      const Vec3 dir = ToVec3(d[x]);
      const int xn = x + 1 < width ? x + 1 : x - 1;
      // A pixel's angular size: its footprint at distance D is about D times this.
      const double pixel = std::max((ToVec3(d[xn]) - dir).norm(), (ToVec3(d_down[x]) - dir).norm());
      for (const BoundingSphere& b : spheres) {
        const Vec3 oc = b.center - origin;
        const double along = oc.dot(dir);
        const double reach = b.radius + 1.5 * pixel * std::max(0.0, along + b.radius);
        if (along < -b.radius) continue;  // behind the camera
        if ((oc - along * dir).squaredNorm() <= reach * reach) {
          begin = std::min(begin, x);
          end = std::max(end, x + 1);
          break;
        }
      }
    }
    if (begin < end) runs[std::size_t(y)] = cv::Vec2i(begin, end);
  });
  return runs;
}

namespace {

// What the sensor does to one row of radiance, with everything it needs held by value: the
// byte stores may alias anything reached through a pointer, so nothing is reloaded per pixel.
struct SensorRow {
  int width = 0, height = 0;
  float half_diagonal2 = 1, v0 = 0, v1 = 0;
  float gain[3] = {1, 1, 1};
  bool noisy = false;
  float full_well = 1, read_variance = 0;
  std::uint64_t seed = 0;
  const std::array<std::uint8_t, 65536>* table = nullptr;

  void operator()(int y, const float* in, std::uint8_t* out) const {
    // One noise stream per row, so rows may run in any order and on any thread.
    NoiseSource noise(seed * 0xD1B54A32D192ED03ull + std::uint64_t(y) * 0x9FB21C65ull);
    const float py = float(y) - 0.5f * float(height - 1);
    for (int x = 0; x < width; ++x) {
      const float px = float(x) - 0.5f * float(width - 1);
      const float rho2 = (px * px + py * py) / half_diagonal2;
      const float falloff = 1.0f + rho2 * (v0 + rho2 * v1);
      for (int ch = 0; ch < 3; ++ch) {
        float v = in[3 * x + ch] * gain[ch] * falloff;
        if (noisy) {
          const float electrons = std::max(0.0f, v) * full_well;
          const float sigma = std::sqrt(electrons + read_variance);
          v = (electrons + sigma * noise.Gaussian()) / full_well;
        }
        out[3 * x + ch] = LinearToSrgb8With(*table, v);
      }
    }
  }
};

}  // namespace

cv::Mat ExposeRadiance(const SimulatedModule& module, const cv::Mat& radiance,
                       const ExposureOptions& options) {
  const CameraIntrinsics& c = module.intrinsics;
  RequireModuleImage(module, radiance, "radiance image");
  SensorRow sensor;
  sensor.width = c.width;
  sensor.height = c.height;
  sensor.half_diagonal2 = float(0.25 * (double(c.width) * c.width + double(c.height) * c.height));
  sensor.v0 = float(module.photometry.vignetting[0]);
  sensor.v1 = float(module.photometry.vignetting[1]);
  for (int ch = 0; ch < 3; ++ch) sensor.gain[ch] = float(module.photometry.gain[ch]);
  sensor.noisy = options.noise;
  sensor.full_well = float(options.full_well);
  sensor.read_variance = float(options.read_noise * options.read_noise);
  sensor.seed = options.noise_seed;
  sensor.table = &LinearToSrgb8EncodeTable();
  cv::Mat image(c.height, c.width, CV_8UC3);
  tbb::parallel_for(tbb::blocked_range<int>(0, c.height, 8), [&](const auto& rows) {
    const SensorRow row = sensor;
    for (int y = rows.begin(); y != rows.end(); ++y)
      row(y, radiance.ptr<float>(y), image.ptr<std::uint8_t>(y));
  });
  return image;
}

cv::Mat ExposeModule(const SimulatedModule& module, const cv::Mat& directions,
                     const PixelRadiance& radiance, const ExposureOptions& options,
                     const cv::Mat* behind) {
  return ExposeRadiance(module, RenderRadiance(module, directions, radiance, behind), options);
}

}  // namespace lfcam
