#include "lfcam/sim/oracle.h"

#include <fmt/format.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdint>
#include <numeric>

#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"
#include "lfcam/render/lens_sampling.h"

namespace lfcam {
namespace {

// A per-pixel offset in [0,1)^2 that decorrelates the lens pattern between pixels.
Vec2 PixelRotation(int i, int j) {
  std::uint32_t h = std::uint32_t(i) * 73856093u ^ std::uint32_t(j) * 19349663u;
  h = (h ^ (h >> 16)) * 0x45d9f3bu;
  h = (h ^ (h >> 16)) * 0x45d9f3bu;
  h ^= h >> 16;
  return {(h & 0xFFFF) / 65536.0, (h >> 16) / 65536.0};
}

// A multiplier coprime to n near the golden section, so that m -> m * p mod n permutes 0..n-1
// and pairs film strata with lens samples without correlation.
int CoprimeNear(int n) {
  for (int p = std::max(1, int(0.618 * n)); p < n + 2; ++p)
    if (std::gcd(p, n) == 1) return p;
  return 1;
}

}  // namespace

int OracleSamplesPerPixel(const VirtualCamera& camera, const OracleOptions& options) {
  if (options.samples_per_pixel > kMaxOracleSamples)
    throw Error(fmt::format("{} oracle samples a pixel is more than the limit of {}",
                            options.samples_per_pixel, kMaxOracleSamples));
  if (options.samples_per_pixel > 0) return options.samples_per_pixel;
  return camera.is_pinhole() ? 256 : 1024;
}

cv::Mat RenderSceneOracle(const Scene& scene, const VirtualCamera& camera,
                          const OracleOptions& options) {
  const int n = OracleSamplesPerPixel(camera, options);
  const int strata = std::max(1, int(std::lround(std::sqrt(double(n)))));
  const int permute = CoprimeNear(n);
  cv::Mat image(camera.height(), camera.width(), CV_32FC3);

  auto render = [&] {
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, camera.height(), 8, 0, camera.width(), 8),
        [&](const tbb::blocked_range2d<int>& r) {
          for (int j = r.rows().begin(); j != r.rows().end(); ++j) {
            auto* row = image.ptr<cv::Vec3f>(camera.image_row(j));
            for (int i = r.cols().begin(); i != r.cols().end(); ++i) {
              const Vec2 rotation = PixelRotation(i, j);
              Vec3 sum = Vec3::Zero();
              for (int m = 0; m < n; ++m) {
                // Film position: stratified over the pixel; lens: rotated Hammersley.
                const int f = int((std::int64_t(m) * permute) % n);
                const int sx = f % strata, sy = (f / strata) % strata;
                const double fx = i + (sx + 0.5) / strata;
                const double fy = j + (sy + 0.5) / strata;
                const Vec3 direction = camera.direction_through(fx, fy);
                if (camera.is_pinhole()) {
                  sum += scene.Radiance({camera.e_c(), direction});
                  continue;
                }
                Vec2 u = Hammersley(m, n) + rotation;
                u = u.array() - u.array().floor();
                const Vec3 lens = camera.lens_point(SampleUniformDiskConcentric(u));
                const Vec3 p_o = camera.focus_point(direction);
                sum += scene.Radiance({lens, p_o - lens});
              }
              sum /= n;
              row[i] = cv::Vec3f(float(sum.x()), float(sum.y()), float(sum.z()));
            }
          }
          if (options.progress)
            options.progress(std::int64_t(r.rows().size()) * std::int64_t(r.cols().size()));
        });
  };
  if (options.threads > 0) {
    tbb::task_arena arena(options.threads);
    arena.execute(render);
  } else {
    render();
  }
  return image;
}

}  // namespace lfcam
