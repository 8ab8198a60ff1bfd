#include "lfcam/sim/oracle.h"

#include <fmt/format.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

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

// Every ray of the rectangle leaves a point of the lens disk (radius a, about e_c, across n_c)
// for a point of the rectangle's image on the plane of focus (depth z_f along -n_c); at depth z it
// lies within (1 - z/z_f) times the disk plus (z/z_f) times that image, inside a box whose low
// edges are concave in z and high edges convex (linear, less or plus |1 - z/z_f| a). Over the
// depths an object's bounding sphere spans, the box of the two ends' boxes holds the whole bundle;
// an object is kept where its sphere's box meets it, and one that reaches the lens's plane
// whatever. Scene::Radiance over these gives what it gives over all.
std::vector<int> ObjectsTheRaysCanMeet(const Scene& scene, const VirtualCamera& camera, double x0,
                                       double y0, double x1, double y1) {
  const Vec3& e = camera.e_c();
  const double z_f = camera.params().focus_distance_mm;
  const double a = 0.5 * std::max(camera.params().aperture_mm, 0.0);
  double fx0 = HUGE_VAL, fx1 = -HUGE_VAL, fy0 = HUGE_VAL, fy1 = -HUGE_VAL;
  for (const double x : {x0, x1})
    for (const double y : {y0, y1}) {
      const Vec3 d = camera.direction_through(x, y);  // its component along -n_c is 1
      const double u = z_f * d.dot(camera.u_c()), v = z_f * d.dot(camera.v_c());
      fx0 = std::min(fx0, u), fx1 = std::max(fx1, u);
      fy0 = std::min(fy0, v), fy1 = std::max(fy1, v);
    }
  std::vector<int> kept;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const BoundingSphere bounds = scene.objects[i].shape->Bounds();
    const Vec3 c = bounds.center - e;
    const double z = -c.dot(camera.n_c()), x = c.dot(camera.u_c()), y = c.dot(camera.v_c());
    // A little wider than the sphere, for the rounding of the rays' own arithmetic.
    const double r = bounds.radius * (1.0 + 1e-9) + 1e-6 * (1.0 + std::abs(z) + a);
    bool meets = !(z - r > 0.0) || !std::isfinite(r);
    if (!meets) {
      double lx0 = HUGE_VAL, lx1 = -HUGE_VAL, ly0 = HUGE_VAL, ly1 = -HUGE_VAL;
      for (const double at : {z - r, z + r}) {
        const double w = at / z_f, spread = std::abs(1.0 - w) * a;
        lx0 = std::min(lx0, w * fx0 - spread), lx1 = std::max(lx1, w * fx1 + spread);
        ly0 = std::min(ly0, w * fy0 - spread), ly1 = std::max(ly1, w * fy1 + spread);
      }
      meets = x + r >= lx0 && x - r <= lx1 && y + r >= ly0 && y - r <= ly1;
    }
    if (meets) kept.push_back(int(i));
  }
  return kept;
}

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
          // Block by block, each ray tested only against the objects its block's rays can meet.
          constexpr int kBlock = 8;
          for (int j0 = r.rows().begin(); j0 < r.rows().end(); j0 += kBlock)
            for (int i0 = r.cols().begin(); i0 < r.cols().end(); i0 += kBlock) {
              const int j1 = std::min(j0 + kBlock, r.rows().end());
              const int i1 = std::min(i0 + kBlock, r.cols().end());
              const std::vector<int> objects = ObjectsTheRaysCanMeet(scene, camera, i0, j0, i1, j1);
              for (int j = j0; j < j1; ++j) {
                auto* row = image.ptr<cv::Vec3f>(camera.image_row(j));
                for (int i = i0; i < i1; ++i) {
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
                      sum += scene.Radiance({camera.e_c(), direction}, objects);
                      continue;
                    }
                    Vec2 u = Hammersley(m, n) + rotation;
                    u = u.array() - u.array().floor();
                    const Vec3 lens = camera.lens_point(SampleUniformDiskConcentric(u));
                    const Vec3 p_o = camera.focus_point(direction);
                    sum += scene.Radiance({lens, p_o - lens}, objects);
                  }
                  sum /= n;
                  row[i] = cv::Vec3f(float(sum.x()), float(sum.y()), float(sum.z()));
                }
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
