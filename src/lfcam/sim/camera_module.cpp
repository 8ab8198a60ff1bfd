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
        m.world_from_camera.translation += uniform(0, 1.0) * array.u_ca +
                                           uniform(0, 1.0) * array.v_ca +
                                           uniform(0, 1.0) * array.n_ca;
        const Vec3 tilt(uniform(0, degree), uniform(0, degree), uniform(0, degree));
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
        m.photometry.gain = exposure * Vec3(uniform(1.0, 0.08), 1.0, uniform(1.0, 0.08));
        m.photometry.vignetting[0] = uniform(-0.30, 0.05);
        m.photometry.vignetting[1] = uniform(-0.05, 0.03);
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
  double Gaussian() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    const double sum = double(z & 0xFFFF) + double((z >> 16) & 0xFFFF) +
                       double((z >> 32) & 0xFFFF) + double(z >> 48);
    // Four uniforms on [0, 1): mean 2, variance 1/3.
    return (sum / 65536.0 - 2.0) * 1.7320508075688772;
  }

 private:
  std::uint64_t state_;
};

// Calls f(x, y, ray, dx, dy) for every pixel, rows in parallel.
template <typename F>
void ForEachPixelRay(const SimulatedModule& module, const cv::Mat& directions, F&& f) {
  const CameraIntrinsics& c = module.intrinsics;
  if (directions.rows != c.height || directions.cols != c.width || directions.type() != CV_32FC3)
    throw Error("the direction map does not match the module");
  const Vec3 origin = module.world_from_camera.translation;
  tbb::parallel_for(tbb::blocked_range<int>(0, c.height, 8), [&](const auto& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      const auto* d = directions.ptr<cv::Vec3f>(y);
      const auto* d_down = directions.ptr<cv::Vec3f>(y + 1 < c.height ? y + 1 : y - 1);
      const double dy_sign = y + 1 < c.height ? 1.0 : -1.0;
      for (int x = 0; x < c.width; ++x) {
        const Vec3 dir = ToVec3(d[x]);
        const int xn = x + 1 < c.width ? x + 1 : x - 1;
        const Vec3 dx = (ToVec3(d[xn]) - dir) * (x + 1 < c.width ? 1.0 : -1.0);
        const Vec3 dy = (ToVec3(d_down[x]) - dir) * dy_sign;
        f(x, y, Ray{origin, dir}, dx, dy);
      }
    }
  });
}

}  // namespace

cv::Mat RenderRadiance(const SimulatedModule& module, const cv::Mat& directions,
                       const PixelRadiance& radiance) {
  cv::Mat out(module.intrinsics.height, module.intrinsics.width, CV_32FC3);
  ForEachPixelRay(module, directions,
                  [&](int x, int y, const Ray& ray, const Vec3& dx, const Vec3& dy) {
                    const Vec3 v = radiance(ray, dx, dy, nullptr);
                    out.at<cv::Vec3f>(y, x) = cv::Vec3f(float(v.x()), float(v.y()), float(v.z()));
                  });
  return out;
}

cv::Mat ExposeModule(const SimulatedModule& module, const cv::Mat& directions,
                     const PixelRadiance& radiance, const ExposureOptions& options,
                     const cv::Mat* behind) {
  const CameraIntrinsics& c = module.intrinsics;
  if (behind && (behind->rows != c.height || behind->cols != c.width || behind->type() != CV_32FC3))
    throw Error("the background image does not match the module");
  const double half_diagonal2 = 0.25 * (double(c.width) * c.width + double(c.height) * c.height);
  cv::Mat image(c.height, c.width, CV_8UC3);
  ForEachPixelRay(
      module, directions, [&](int x, int y, const Ray& ray, const Vec3& dx, const Vec3& dy) {
        // One noise stream per pixel, so rows may run in any order and on any thread.
        NoiseSource noise(options.noise_seed * 0xD1B54A32D192ED03ull +
                          std::uint64_t(y) * std::uint64_t(c.width) + std::uint64_t(x));
        Vec3 back;
        if (behind) {
          const cv::Vec3f b = behind->at<cv::Vec3f>(y, x);
          back = Vec3(b[0], b[1], b[2]);
        }
        Vec3 value = radiance(ray, dx, dy, behind ? &back : nullptr);
        const double px = x - 0.5 * (c.width - 1), py = y - 0.5 * (c.height - 1);
        const double falloff = module.photometry.falloff((px * px + py * py) / half_diagonal2);
        value = value.cwiseProduct(module.photometry.gain) * falloff;
        cv::Vec3b encoded;
        for (int ch = 0; ch < 3; ++ch) {
          double v = value[ch];
          if (options.noise) {
            const double electrons = std::max(0.0, v) * options.full_well;
            const double sigma = std::sqrt(electrons + options.read_noise * options.read_noise);
            v = (electrons + sigma * noise.Gaussian()) / options.full_well;
          }
          encoded[ch] = LinearToSrgb8Table(float(v));
        }
        image.at<cv::Vec3b>(y, x) = encoded;
      });
  return image;
}

}  // namespace lfcam
