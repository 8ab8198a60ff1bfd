#include "lfcam/render/separable_frame.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "lfcam/render/camera_integrator.h"
#include "lfcam/render/lightfield_sampler.h"
#include "lfcam/render/ray_setup.h"
#include "lfcam/render/simd_kernels.h"

namespace lfcam {
namespace {

// How far (in samples, or mm for the array's plane) a frame may stray from separability.
constexpr double kSampleTolerance = 1e-6;
constexpr double kPlaneTolerance = 1e-9;

// The map along one axis: x(n) = x0 + lambda (x_at(n) - x_o) for the n pixels, `padded` long.
AxisMap MakeAxisMap(int pixels, int padded, int samples, double x0, double lambda,
                    const PixelAffine& along, double x_o, bool columns) {
  AxisMap m;
  m.i0.assign(std::size_t(padded), 0);
  m.i1.assign(std::size_t(padded), 0);
  m.w0.assign(std::size_t(padded), 0.0f);
  m.w1.assign(std::size_t(padded), 0.0f);
  m.inside.assign(std::size_t(padded), 0.0f);
  m.lo = samples;
  m.hi = 0;
  for (int n = 0; n < pixels; ++n) {
    const double at = columns ? along.at(n, 0) : along.at(0, n);
    const double x = x0 + lambda * (at - x_o);
    const AxisLerp lerp = AxisLerp::At(x, samples);
    const std::size_t s = std::size_t(n);
    m.i0[s] = lerp.i0;
    m.i1[s] = lerp.i1;
    m.w0[s] = 1.0f - lerp.w1;
    m.w1[s] = lerp.w1;
    m.inside[s] = x >= -0.5 && x <= samples - 0.5 ? 1.0f : 0.0f;
    m.lo = std::min(m.lo, lerp.i0);
    m.hi = std::max(m.hi, lerp.i1);
  }
  for (int n = pixels; n < padded; ++n) m.i0[std::size_t(n)] = m.i1[std::size_t(n)] = m.lo;
  return m;
}

class Builder {
 public:
  Builder(const LightField& lf, const VirtualCamera& camera)
      : lf_(lf), camera_(camera), st_(StSamplePlane(lf)), affines_(st_.Affines(camera)) {
    frame_.width = camera.width();
    frame_.height = camera.height();
    // Separable: the plane of focus parallel to the st-plane (every origin's lambda is the
    // same for all pixels), k along the pixel columns only, l along the rows only.
    const double w = camera.width(), h = camera.height();
    separable_ = std::abs(affines_.n.di) * w + std::abs(affines_.n.dj) * h <
                     kPlaneTolerance * std::max(1.0, std::abs(affines_.n.at00)) &&
                 std::abs(affines_.x.dj) * h < kSampleTolerance &&
                 std::abs(affines_.y.di) * w < kSampleTolerance;
  }
  bool separable() const { return separable_; }

  // Adds the maps of the lines from `origin`; -1 when they run parallel to the st-plane.
  int AddOrigin(const Vec3& origin) {
    const double den = affines_.n.at00 - st_.n.dot(origin);
    if (den == 0.0) return -1;
    const double lambda = st_.n.dot(st_.q - origin) / den;
    const double x0 = st_.a_x.dot(origin - st_.q) + st_.x_offset;
    const double y0 = st_.a_y.dot(origin - st_.q) + st_.y_offset;
    const int padded = PaddedRowWidth(camera_.width());
    frame_.origins.push_back({MakeAxisMap(camera_.width(), padded, lf_.dims().n_s, x0, lambda,
                                          affines_.x, st_.a_x.dot(origin), true),
                              MakeAxisMap(camera_.height(), camera_.height(), lf_.dims().n_t, y0,
                                          lambda, affines_.y, st_.a_y.dot(origin), false)});
    return int(frame_.origins.size()) - 1;
  }
  int CameraOrigin(int view) {
    auto [it, added] = camera_origins_.try_emplace(view, -1);
    if (added)
      it->second = AddOrigin(lf_.camera_center(view / lf_.dims().cols, view % lf_.dims().cols));
    return it->second;
  }
  SeparableFrame& frame() { return frame_; }

 private:
  const LightField& lf_;
  const VirtualCamera& camera_;
  SamplePlane st_;
  PlaneAffines affines_;
  bool separable_ = false;
  SeparableFrame frame_;
  std::map<int, int> camera_origins_;
};

}  // namespace

std::optional<SeparableFrame> MakeSeparableFrame(const LightField& lf, const VirtualCamera& camera,
                                                 const CpuRenderOptions& options) {
  if (!FastKernelsSupport(lf)) return std::nullopt;
  Builder builder(lf, camera);
  if (!builder.separable()) return std::nullopt;
  const int cols = lf.dims().cols, rows = lf.dims().rows;
  SeparableFrame& frame = builder.frame();

  if (options.integrator == Integrator::kCameras && !camera.is_pinhole()) {
    const CameraIntegratorFrame cameras(lf, camera);
    const auto& uniform = cameras.uniform_weights();
    if (uniform.empty()) return std::nullopt;
    frame.eye = builder.AddOrigin(camera.e_c());
    if (frame.eye < 0) return std::nullopt;
    for (const GridCameraWeight& c : uniform) {
      const int read = builder.CameraOrigin(c.row * cols + c.col);
      if (read < 0) return std::nullopt;  // the reference skips such a camera; rare, and slow
      frame.terms.push_back({c.row * cols + c.col, read, frame.eye, float(c.weight)});
    }
    frame.reads_per_pixel = int(uniform.size());
    return std::move(frame);
  }

  // Lens samples (a pinhole is one, at the eye): each must lie on the array's plane.
  const bool focal_plane = options.integrator == Integrator::kCameras ||
                           options.interpolation == Interpolation::kFocalPlane;
  const SamplePlane uv = UvSamplePlane(lf);
  for (const Vec2& disk : camera.lens_samples()) {
    const Vec3 lens = camera.lens_point(disk);
    if (std::abs(uv.n.dot(uv.q - lens)) > kPlaneTolerance * std::max(1.0, uv.q.norm()))
      return std::nullopt;
    const double cx = uv.a_x.dot(lens - uv.q) + uv.x_offset;
    const double cy = uv.a_y.dot(lens - uv.q) + uv.y_offset;
    if (!(cx >= -0.5 && cx <= cols - 0.5 && cy >= -0.5 && cy <= rows - 0.5)) continue;
    const int mask = builder.AddOrigin(lens);
    if (mask < 0) continue;  // parallel to the st-plane: the reference misses too
    frame.hit_origins.push_back(mask);
    const AxisLerp c = AxisLerp::At(cx, cols), r = AxisLerp::At(cy, rows);
    const int view_r[2] = {r.i0, r.i1}, view_c[2] = {c.i0, c.i1};
    const float wr[2] = {1.0f - r.w1, r.w1}, wc[2] = {1.0f - c.w1, c.w1};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const float w = wr[a] * wc[b];
        if (w == 0.0f) continue;
        const int view = view_r[a] * cols + view_c[b];
        const int read = focal_plane ? builder.CameraOrigin(view) : mask;
        if (read < 0) return std::nullopt;
        frame.terms.push_back({view, read, mask, w});
      }
  }
  return std::move(frame);
}

}  // namespace lfcam
