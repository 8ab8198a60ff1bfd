#include "lfcam/render/separable_frame.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "lfcam/render/camera_integrator.h"
#include "lfcam/render/lightfield_sampler.h"
#include "lfcam/render/simd_kernels.h"

namespace lfcam {
namespace {

constexpr double kPlaneTolerance = 1e-9;

// How fast, at most over the frame, an origin's k changes along the pixel rows and its l along
// the pixel columns (samples per pixel): the maps' drift off their own axis.
struct Drift {
  double dk_dj = 0;      // the most
  double dl_dj = 1e300;  // the least: how fast the sample rows go by
  double dl_row = 0;     // the most l changes along a pixel row (the first or the last)
  // The most l at a row's ends strays from l at its middle column (where the band resamples
  // each sample row for the pixel row that reads it there): the rows that read a sample row at
  // a row's ends lie that much farther off.
  double dl_mid = 0;
};

class Builder {
 public:
  Builder(const LightField& lf, const VirtualCamera& camera)
      : lf_(lf), camera_(camera), st_(StSamplePlane(lf)) {
    frame_.st = st_.Affines(camera);
    frame_.width = camera.width();
    frame_.height = camera.height();
  }

  // Adds the lines from `origin`; -1 when some of them run (nearly) parallel to the st-plane.
  int AddOrigin(const Vec3& origin) {
    const int w = camera_.width() - 1, h = camera_.height() - 1;
    double den_lo = 1e300, den_hi = -1e300;
    double l_at[4] = {};
    int corner = 0;
    for (const auto& [i, j] : {std::pair{0, 0}, {w, 0}, {0, h}, {w, h}}) {
      const Vec3 p = camera_.focus_point(camera_.pixel_direction(i, j));
      const double den = st_.n.dot(p - origin);
      den_lo = std::min(den_lo, den);
      den_hi = std::max(den_hi, den);
      double k, l, k_down, l_down;
      const Vec3 down = camera_.focus_point(camera_.pixel_direction(i, j + (j < h ? 1 : -1)));
      if (!st_.Coordinates(origin, p, &k, &l) || !st_.Coordinates(origin, down, &k_down, &l_down))
        return -1;
      drift_.dk_dj = std::max(drift_.dk_dj, std::abs(k_down - k));
      drift_.dl_dj = std::min(drift_.dl_dj, std::abs(l_down - l));
      l_at[corner++] = l;
    }
    drift_.dl_row =
        std::max({drift_.dl_row, std::abs(l_at[1] - l_at[0]), std::abs(l_at[3] - l_at[2])});
    for (const int j : {0, h}) {
      // Between the pixel centres either side of the middle (the band's is at w / 2).
      for (const int i : {w / 2, (w + 1) / 2}) {
        double k, l;
        if (!st_.Coordinates(origin, camera_.focus_point(camera_.pixel_direction(i, j)), &k, &l))
          return -1;
        const double* ends = j == 0 ? l_at : l_at + 2;
        drift_.dl_mid = std::max({drift_.dl_mid, std::abs(ends[0] - l), std::abs(ends[1] - l)});
      }
    }
    // The denominator keeps one sign, well away from zero, over the frame.
    if (!(den_lo > 0 || den_hi < 0) || std::min(std::abs(den_lo), std::abs(den_hi)) < 1e-6)
      return -1;
    frame_.origins.push_back(st_.Origin(origin));
    return int(frame_.origins.size()) - 1;
  }
  int CameraOrigin(int view) {
    auto [it, added] = camera_origins_.try_emplace(view, -1);
    if (added)
      it->second = AddOrigin(lf_.camera_center(view / lf_.dims().cols, view % lf_.dims().cols));
    return it->second;
  }

  // The most a resampled row's k strays from a pixel's own; beyond the tolerance, how often
  // each sample row is resampled again (false where that would cost a pixel row more sample
  // rows resampled than the cameras integrator's row kernel takes, kMaxResampledRows).
  bool WithinTolerance() {
    // The rows that read a sample row lie within 1 / |dl/dj| of where l crosses it at the
    // middle column, and farther by how much l changes from there along the row.
    const double rows = drift_.dl_dj > 0 ? (1.0 + drift_.dl_mid) / drift_.dl_dj : 1e300;
    frame_.map_error = drift_.dk_dj * rows;
    if (frame_.map_error <= kSeparableTolerance) return true;
    const double groups = std::floor(kSeparableTolerance / drift_.dk_dj);
    frame_.resample_every = 1 + 2 * int(std::min(groups, 64.0));
    // A group of pixel rows resamples the sample rows it crosses, about dl_row + 2 a row.
    if (!((drift_.dl_row + 2) / frame_.resample_every <= kMaxResampledRows)) return false;
    frame_.map_error = drift_.dk_dj * 0.5 * (frame_.resample_every - 1);
    return true;
  }
  SeparableFrame& frame() { return frame_; }

  // Views with their own windows: each term reads its view in the view's own samples (its read
  // origin moved by the window's offset). Where every term's reads stay inside its view's window
  // over the whole frame, no blend needs renormalising and the frame stays separable; otherwise
  // false (the per-pixel kernels renormalise). The maps are monotonic over the frame: the
  // corners bound them. With a taper (`tapered`: the cameras integrator's) each term's reads
  // count by their share of the window wherever they go, renormalised as at the domain's edge:
  // the frame stays separable.
  bool ReadsInsideTheirWindows(bool tapered) {
    if (!lf_.has_view_windows()) return true;
    const int w = camera_.width() - 1, h = camera_.height() - 1;
    const double k_hi = lf_.dims().n_s - 0.5, l_hi = lf_.dims().n_t - 0.5;
    for (SeparableTerm& t : frame_.terms) {
      const StOffset o = lf_.st_offset(t.view / lf_.dims().cols, t.view % lf_.dims().cols);
      OriginConstants read = frame_.origins[std::size_t(t.read)];
      read.x0 -= float(o.k);
      read.y0 -= float(o.l);
      for (const auto& [i, j] : {std::pair{0, 0}, {w, 0}, {0, h}, {w, h}}) {
        const double lambda = read.num / (frame_.st.n.at(i, j) - read.n_o);
        const double k = read.x0 + lambda * (frame_.st.x.at(i, j) - read.x_o);
        const double l = read.y0 + lambda * (frame_.st.y.at(i, j) - read.y_o);
        if (!tapered && !(k >= -0.5 && k <= k_hi && l >= -0.5 && l <= l_hi)) return false;
      }
      frame_.origins.push_back(read);
      t.read = int(frame_.origins.size()) - 1;
    }
    return true;
  }

 private:
  const LightField& lf_;
  const VirtualCamera& camera_;
  SamplePlane st_;
  SeparableFrame frame_;
  Drift drift_;
  std::map<int, int> camera_origins_;
};

// `per_pixel`: the cameras' weights may differ from pixel to pixel (they then come from
// `cameras` row by row, which must outlive the frame).
bool BuildCamerasIntegrator(const LightField& lf, const VirtualCamera& camera,
                            const CameraIntegratorFrame& cameras, bool per_pixel,
                            Builder& builder) {
  const auto& uniform = cameras.uniform_weights();
  SeparableFrame& frame = builder.frame();
  const int cols = lf.dims().cols;
  std::vector<SeparableTerm> terms;
  if (!uniform.empty()) {
    for (const GridCameraWeight& c : uniform)
      terms.push_back({c.row * cols + c.col, 0, 0, float(c.weight)});
  } else {
    // Every camera some pixel weighs, each pixel by its own footprint (from the table). A turned
    // camera keeps the maps separable only when turned about the array's vertical axis: the
    // drift decides.
    if (!per_pixel || cameras.levels().empty()) return false;
    const std::vector<bool> read = cameras.CamerasRead();
    for (std::size_t view = 0; view < read.size(); ++view)
      if (read[view]) terms.push_back({int(view), 0, 0, 1.0f});
    if (terms.empty()) return false;  // no pixel reads a camera: nothing to separate
    frame.pixel_weights = &cameras;
  }
  frame.eye = builder.AddOrigin(camera.e_c());
  if (frame.eye < 0) return false;
  for (SeparableTerm& t : terms) {
    t.read = t.mask = builder.CameraOrigin(t.view);
    if (t.read < 0) return false;
    // Each camera counts where its own line through p_o meets the domain (RenderPixelCameras).
    frame.terms.push_back(t);
  }
  frame.reads_per_pixel = int(frame.terms.size());
  if (frame.pixel_weights != nullptr) {
    // A band's weights are held for all its rows at once: bands of fewer rows where the row's
    // cameras are many, so that they stay near 4 MB.
    const double row_bytes = 4.0 * double(lf.dims().view_count()) * PaddedRowWidth(camera.width());
    frame.band_rows = std::clamp(int((4 << 20) / row_bytes), 4, frame.band_rows);
  }
  return true;
}

// Lens samples (a pinhole is one, at the eye): each must lie on the array's plane.
bool BuildLensSamples(const LightField& lf, const VirtualCamera& camera, bool focal_plane,
                      Builder& builder) {
  const int cols = lf.dims().cols, rows = lf.dims().rows;
  SeparableFrame& frame = builder.frame();
  const SamplePlane uv = UvSamplePlane(lf);
  for (const Vec2& disk : camera.lens_samples()) {
    const Vec3 lens = camera.lens_point(disk);
    if (std::abs(uv.n.dot(uv.q - lens)) > kPlaneTolerance * std::max(1.0, uv.q.norm()))
      return false;
    const double cx = uv.a_x.dot(lens - uv.q) + uv.x_offset;
    const double cy = uv.a_y.dot(lens - uv.q) + uv.y_offset;
    if (!(cx >= -0.5 && cx <= cols - 0.5 && cy >= -0.5 && cy <= rows - 0.5)) continue;
    const int mask = builder.AddOrigin(lens);
    if (mask < 0) return false;
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
        if (read < 0) return false;
        frame.terms.push_back({view, read, mask, w});
      }
  }
  return true;
}

}  // namespace

std::optional<SeparableFrame> MakeSeparableFrame(const LightField& lf, const VirtualCamera& camera,
                                                 const CpuRenderOptions& options,
                                                 const CameraIntegratorFrame* cameras) {
  if (!RowKernelsSupport(lf)) return std::nullopt;
  Builder builder(lf, camera);
  const bool focal_plane = options.integrator == Integrator::kCameras ||
                           options.interpolation == Interpolation::kFocalPlane;
  bool built = false;
  if (options.integrator == Integrator::kCameras && !camera.is_pinhole()) {
    std::optional<CameraIntegratorFrame> own;
    built = BuildCamerasIntegrator(lf, camera, cameras ? *cameras : own.emplace(lf, camera),
                                   cameras != nullptr, builder);
  } else {
    built = BuildLensSamples(lf, camera, focal_plane, builder);
  }
  const bool tapered = options.window_taper != nullptr && builder.frame().eye >= 0;
  if (!built || !builder.WithinTolerance() || !builder.ReadsInsideTheirWindows(tapered))
    return std::nullopt;
  return std::move(builder.frame());
}

}  // namespace lfcam
