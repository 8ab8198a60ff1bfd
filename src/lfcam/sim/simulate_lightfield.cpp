#include "lfcam/sim/simulate_lightfield.h"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <vector>

#include "lfcam/core/camera_model.h"
#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"

namespace lfcam {

ArrayPlane ResizeArray(const ArrayPlane& array, int rows, int cols) {
  if (rows < 1 || cols < 1 || rows > kMaxViewsPerSide || cols > kMaxViewsPerSide)
    throw Error(fmt::format("camera grid {}x{} is out of range", rows, cols));
  const Vec3 center = array.center();
  ArrayPlane out = array;
  out.rows = rows;
  out.cols = cols;
  out.p_ca = center - 0.5 * out.width_mm() * out.u_ca - 0.5 * out.height_mm() * out.v_ca;
  return out;
}

namespace {

// Where each of the scene's objects can appear among a view's samples: a box of continuous
// sample coordinates holding the central projection, from the camera's centre onto the
// st-plane, of the box around the object's bounding sphere (the projection of a convex set in
// front of the camera is the hull of its corners' projections), widened by 2 samples for the
// sub-samples (half a sample from a sample's centre) and rounding. An object not wholly in front
// of the camera gets every sample. A ray through a sample outside an object's box cannot meet
// the object, so leaving it out of that ray's tests changes no sample.
struct SampleBox {
  double k0 = -HUGE_VAL, k1 = HUGE_VAL, l0 = -HUGE_VAL, l1 = HUGE_VAL;
  bool Holds(double k, double l) const { return k >= k0 && k <= k1 && l >= l0 && l <= l1; }
};

std::vector<SampleBox> ObjectSampleBoxes(const Scene& scene, const Vec3& center,
                                         const StSampling& sampling) {
  constexpr double kMarginSamples = 2.0;
  const Vec3 normal = sampling.window.normal();
  const double to_plane = normal.dot(sampling.window.origin - center);
  std::vector<SampleBox> boxes(scene.objects.size());
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const BoundingSphere bounds = scene.objects[i].shape->Bounds();
    SampleBox box{HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL};
    bool in_front = std::abs(to_plane) > 0;
    for (int corner = 0; corner < 8 && in_front; ++corner) {
      const Vec3 offset((corner & 1) ? bounds.radius : -bounds.radius,
                        (corner & 2) ? bounds.radius : -bounds.radius,
                        (corner & 4) ? bounds.radius : -bounds.radius);
      const Vec3 d = bounds.center + offset - center;
      const double along = normal.dot(d);
      // In front: on the plane's side of the camera, and not beside it.
      if (!(along / to_plane > 1e-6)) {
        in_front = false;
        break;
      }
      const Vec2 at = sampling.SampleOf(center + d * (to_plane / along));
      box.k0 = std::min(box.k0, at.x()), box.k1 = std::max(box.k1, at.x());
      box.l0 = std::min(box.l0, at.y()), box.l1 = std::max(box.l1, at.y());
    }
    if (in_front && std::isfinite(box.k0) && std::isfinite(box.k1) && std::isfinite(box.l0) &&
        std::isfinite(box.l1))
      boxes[i] = {box.k0 - kMarginSamples, box.k1 + kMarginSamples, box.l0 - kMarginSamples,
                  box.l1 + kMarginSamples};
  }
  return boxes;
}

}  // namespace

LightField SimulateLightField(const Scene& scene, const SimulateLightFieldOptions& o) {
  if (o.n_s < 1 || o.n_t < 1 || o.n_s > kMaxStSamplesPerSide || o.n_t > kMaxStSamplesPerSide)
    throw Error(fmt::format("st resolution {}x{} is out of range", o.n_s, o.n_t));
  if (o.supersampling < 1 || o.supersampling > 16)
    throw Error(fmt::format("supersampling {} must be 1..16", o.supersampling));
  const double bytes =
      double(o.rows) * o.cols * o.n_s * o.n_t * 3 * double(BytesPerChannel(o.sample_type));
  RequireMemory(bytes,
                fmt::format("a {}x{} light field of {}x{} samples", o.rows, o.cols, o.n_s, o.n_t));
  Slab slab = scene.IdealSlab(o.st_domain);
  slab.uv = ResizeArray(slab.uv, o.rows, o.cols);
  slab.validate();
  LightField lf({o.rows, o.cols, o.n_s, o.n_t}, o.sample_type, slab);
  if (!o.camera_centers.empty()) {
    if (o.camera_centers.size() != lf.dims().view_count())
      throw Error(fmt::format("{} camera centres for {}x{} views", o.camera_centers.size(), o.rows,
                              o.cols));
    std::vector<ViewPose> poses;
    const Mat3 ideal = WorldFromCameraRotation(slab.uv.u_ca, slab.uv.v_ca, slab.uv.n_ca);
    for (const Vec3& c : o.camera_centers) poses.push_back({c, ideal, std::nullopt});
    lf.set_measured_poses(std::move(poses));
  }
  const auto now = std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now());
  lf.metadata() = {{"source", "simulated"},
                   {"scene", scene.name},
                   {"supersampling", o.supersampling},
                   {"created", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", now)}};

  const int ss = o.supersampling;
  const double inv_ss2 = 1.0 / (ss * ss);
  const StSampling sampling = lf.st_sampling();
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  const int total = o.rows * o.cols;
  tbb::parallel_for(0, total, [&](int view) {
    const int row = view / o.cols, col = view % o.cols;
    const Vec3 center = lf.camera_center(row, col);
    const std::vector<SampleBox> boxes = ObjectSampleBoxes(scene, center, sampling);
    tbb::parallel_for(tbb::blocked_range<int>(0, o.n_t, 8), [&](const tbb::blocked_range<int>& r) {
      std::vector<int> candidates;
      candidates.reserve(boxes.size());
      for (int l = r.begin(); l != r.end(); ++l) {
        for (int k = 0; k < o.n_s; ++k) {
          candidates.clear();
          for (std::size_t i = 0; i < boxes.size(); ++i)
            if (boxes[i].Holds(k, l)) candidates.push_back(int(i));
          Vec3 sum = Vec3::Zero();
          for (int a = 0; a < ss; ++a)
            for (int b = 0; b < ss; ++b) {
              // Sub-sample (a, b) of sample (k, l), spread evenly over its cell.
              const Vec3 at = sampling.Point(k - 0.5 + (b + 0.5) / ss, l - 0.5 + (a + 0.5) / ss);
              sum += scene.Radiance({center, at - center}, candidates);
            }
          lf.set_linear_rgb(row, col, k, l, (sum * inv_ss2).cast<float>());
        }
      }
    });
    const int n = ++done;
    if (o.progress) {
      std::lock_guard lock(progress_mutex);
      o.progress(n, total);
    }
  });
  return lf;
}

}  // namespace lfcam
