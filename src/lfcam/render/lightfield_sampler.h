#pragma once
// Radiance lookup in a discrete light field (§6.2): a line meets the uv- and st-planes, and the
// radiance is the quadrilinear blend of the 16 nearest samples, taken in linear light.
// Coordinates clamp to the outermost samples inside the windows; lines outside the PRP window
// or the sampled st domain miss. Where the views have their own st windows (format version 4),
// a view is read only inside its window and the blend renormalises over the views that hold
// the point.
//
// Besides the paper's lookup there is the focal-plane lookup of Isaksen, McMillan and Gortler
// (Dynamically reparameterized light fields, 2000): the four nearest cameras are blended as
// before, but each is read where its own ray toward the point in focus p_o meets the st-plane,
// so that whatever lies on the plane of focus is reconstructed without ghosting.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "lfcam/core/color.h"
#include "lfcam/core/keys_cubic.h"
#include "lfcam/core/lightfield.h"
#include "lfcam/render/window_taper.h"

namespace lfcam {

enum class Interpolation {
  kQuadrilinear,  // the paper's: (u, v, s, t) of the ray itself
  kFocalPlane,    // Isaksen et al.: each camera's own ray through p_o
  kDepth,         // each camera read where the scene point the ray hits projects (depth maps:
                  // render/depth_aware_sampler.h)
};
std::string ToString(Interpolation interpolation);
Interpolation InterpolationFromString(const std::string& name);  // throws lfcam::Error

// Continuous sample coordinate along one axis: position x in sample units (sample i's centre at
// i), clamped, split into two indices and the weight of the second.
struct AxisLerp {
  int i0, i1;
  float w1;
  static AxisLerp At(double x, int n) {
    if (n == 1) return {0, 0, 0.0f};
    x = std::clamp(x, 0.0, double(n - 1));
    const int i = std::min(int(x), n - 2);
    return {i, i + 1, float(x - i)};
  }
};

// The planes a lookup intersects lines with, in the form the samplers use: the uv-plane (p_ca,
// its normal, its axes divided by the window's size), the st-plane (origin, normal, axes divided
// by the window's size), the reference grid (s0, t0 and the scales to samples) and the sampled
// domain (the union of the views' windows).
struct LookupPlanes {
  Vec3 p_ca, n_ca, u_scaled, v_scaled;
  Vec3 st_origin, n_st, s_scaled, t_scaled;
  double s0 = 0, t0 = 0, s_to_k = 0, t_to_l = 0;
  double u_s0 = 0, u_s1 = 0, u_t0 = 0, u_t1 = 0;
};
LookupPlanes LookupPlanesOf(const LightField& lf);

class LightFieldSampler {
 public:
  explicit LightFieldSampler(const LightField& lf);

  int rows() const { return rows_; }
  int cols() const { return cols_; }

  // Radiance along the line (origin, direction); false when it misses the slab (the hot-path
  // twin of Slab::intersect + Slab::contains, with the plane constants precomputed). With
  // kFocalPlane, `p_o` is the point in focus on the line.
  bool Sample(const Vec3& origin, const Vec3& direction, float rgb[3],
              Interpolation interpolation = Interpolation::kQuadrilinear,
              const Vec3& p_o = Vec3::Zero()) const {
    const double n_uv = n_ca_.dot(direction), n_st = n_st_.dot(direction);
    if (n_uv == 0.0 || n_st == 0.0) return false;
    const Vec3 at_uv = origin + (n_ca_.dot(p_ca_ - origin) / n_uv) * direction - p_ca_;
    const double u = at_uv.dot(u_scaled_), v = at_uv.dot(v_scaled_);
    if (!(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0)) return false;
    const Vec3 at_st = origin + (n_st_.dot(st_origin_ - origin) / n_st) * direction - st_origin_;
    const double s = at_st.dot(s_scaled_), t = at_st.dot(t_scaled_);
    if (!(s >= u_s0_ && s <= u_s1_ && t >= u_t0_ && t <= u_t1_)) return false;
    return interpolation == Interpolation::kQuadrilinear ? Fetch(u, v, s, t, rgb)
                                                         : FetchFocused(u, v, p_o, rgb);
  }

  // Whether the line (origin, direction) meets the st-plane inside the sampled st domain (the
  // union of the views' windows).
  bool MeetsStDomain(const Vec3& origin, const Vec3& direction) const {
    const double n_st = n_st_.dot(direction);
    if (n_st == 0.0) return false;
    const Vec3 at_st = origin + (n_st_.dot(st_origin_ - origin) / n_st) * direction - st_origin_;
    const double s = at_st.dot(s_scaled_), t = at_st.dot(t_scaled_);
    return s >= u_s0_ && s <= u_s1_ && t >= u_t0_ && t <= u_t1_;
  }

  // Quadrilinear fetch at window coordinates (u, v) and st-plane coordinates (s, t). False when no
  // view's window holds (s, t) (views with their own windows; with shared windows it always
  // reads, coordinates clamped to the sampled domain).
  bool Fetch(double u, double v, double s, double t, float rgb[3]) const {
    const AxisLerp c = AxisLerp::At(u * cols_ - 0.5, cols_);
    const AxisLerp r = AxisLerp::At(v * rows_ - 0.5, rows_);
    const double k = (s - s0_) * s_to_k_ - 0.5, l = (t - t0_) * t_to_l_ - 0.5;
    float acc[3] = {0, 0, 0}, weight = 0;
    ForNearestCameras(
        c, r, [&](int row, int col, float w) { weight += AccumulateAt(row, col, k, l, w, acc); });
    return Normalise(acc, weight, rgb);
  }

  // Focal-plane fetch: the cameras around (u, v), each read where its ray to p_o meets the
  // st-plane (false as Fetch).
  bool FetchFocused(double u, double v, const Vec3& p_o, float rgb[3]) const {
    const AxisLerp c = AxisLerp::At(u * cols_ - 0.5, cols_);
    const AxisLerp r = AxisLerp::At(v * rows_ - 0.5, rows_);
    float acc[3] = {0, 0, 0}, weight = 0;
    ForNearestCameras(c, r, [&](int row, int col, float w) {
      weight += AccumulateFocused(row, col, p_o, w, acc);
    });
    return Normalise(acc, weight, rgb);
  }

  // acc += w * view (row, col) read bilinearly at continuous reference sample coordinates (k, l)
  // (sample centres at integers). Returns the weight it added: w, or 0 where (k, l) lies outside
  // the view's own window (a light field whose views have their own windows: the caller
  // renormalises over the views that hold the point); with shared windows it clamps to the
  // sampled domain and always reads.
  float AccumulateAt(int row, int col, double k, double l, float w, float acc[3]) const {
    if (!InOwnWindow(row, col, k, l)) return 0.0f;
    AccumulateView(row, col, AxisLerp::At(k, n_s_), AxisLerp::At(l, n_t_), w, acc);
    return w;
  }

  // As AccumulateAt, read with Keys' cubic convolution (a = -0.5) over 4 x 4 samples, the
  // view's edge repeated: between samples bilinear reads blur by up to half a sample, which a
  // blend of a few views read at fractional positions (the depth lookup) shows as softness.
  // 8-bit views are interpolated in their sRGB encoding and the result decoded (the blend of
  // views stays in linear light): a photograph is smooth in the encoding it was filtered in (a
  // camera's processing, a rectification's or resize's resampling, JPEG's blocks), and Keys'
  // overshoot beside an edge, taken in linear light, lands where the encoding is steepest, on
  // the dark side (docs/fidelity.md, "Reading a photograph between its samples").
  float AccumulateAtCubic(int row, int col, double k, double l, float w, float acc[3]) const {
    if (!InOwnWindow(row, col, k, l)) return 0.0f;
    if (srgb8_)
      AccumulateCubicTyped<std::uint8_t>(row, col, k, l, w, acc);
    else
      AccumulateCubicTyped<Eigen::half>(row, col, k, l, w, acc);
    return w;
  }

  // Where the line from `from` through `to` meets the st-plane, in continuous reference sample
  // coordinates (k, l) (sample centres at integers, not clamped); false when it runs parallel to
  // the plane.
  bool StSampleAt(const Vec3& from, const Vec3& to, double& k, double& l) const {
    const Vec3 d = to - from;
    const double n_st = n_st_.dot(d);
    if (n_st == 0.0) return false;
    const Vec3 at_st = from + (n_st_.dot(st_origin_ - from) / n_st) * d - st_origin_;
    k = (at_st.dot(s_scaled_) - s0_) * s_to_k_ - 0.5;
    l = (at_st.dot(t_scaled_) - t0_) * t_to_l_ - 0.5;
    return true;
  }

  // Where the lines from `from` through the points a + x * b of another line meet the st-plane,
  // as a function of x: precomputed once, each point then costs a few multiplies and one
  // division instead of a plane intersection (the depth lookup's march, which visits hundreds of
  // points of a ray in each camera).
  struct LineProjection {
    double k0, l0, ka, kb, la, lb, wa, wb;
    // The point at x = 1 / q (q != 0): k = k0 + (ka q + kb) / (wa q + wb); false when its line
    // runs parallel to the st-plane.
    bool AtReciprocal(double q, double& k, double& l) const {
      const double w = wa * q + wb;
      if (w == 0.0) return false;
      k = k0 + (ka * q + kb) / w;
      l = l0 + (la * q + lb) / w;
      return true;
    }
  };
  LineProjection ProjectLine(const Vec3& from, const Vec3& a, const Vec3& b) const {
    // StSampleAt(from, a + x b) with d = (a - from) + x b: the plane's point is
    // from + (n . (origin - from)) / (n . d) * d, linear in d over n . d.
    const Vec3 rel = from - st_origin_, a_rel = a - from;
    const double g = n_st_.dot(-rel);
    return {(rel.dot(s_scaled_) - s0_) * s_to_k_ - 0.5,
            (rel.dot(t_scaled_) - t0_) * t_to_l_ - 0.5,
            g * s_to_k_ * a_rel.dot(s_scaled_),
            g * s_to_k_ * b.dot(s_scaled_),
            g * t_to_l_ * a_rel.dot(t_scaled_),
            g * t_to_l_ * b.dot(t_scaled_),
            n_st_.dot(a_rel),
            n_st_.dot(b)};
  }

  // acc += w * camera (row, col) read where its own ray toward p_o meets the st-plane
  // (bilinearly; the weight it added, as AccumulateAt).
  float AccumulateFocused(int row, int col, const Vec3& p_o, float w, float acc[3]) const {
    double k, l;
    if (!StSampleAt(camera_centers_[std::size_t(row) * cols_ + col], p_o, k, l)) return 0.0f;
    return AccumulateAt(row, col, k, l, w, acc);
  }

  // As AccumulateFocused, the camera counted by the share of its tent inside its view's window
  // (render/window_taper.h) rather than wholly or not at all: adds w times that share, read at
  // the point clamped to the view's samples, and returns it.
  float AccumulateFocusedTapered(int row, int col, const Vec3& p_o, float w,
                                 const WindowTaper& taper, float acc[3]) const {
    const std::size_t index = std::size_t(row) * cols_ + col;
    double k, l;
    if (!StSampleAt(camera_centers_[index], p_o, k, l)) return 0.0f;
    if (!offsets_.empty()) {
      k -= offsets_[index].k;
      l -= offsets_[index].l;
    }
    const float held = w * float(taper.Share(int(index), k, l));
    if (!(held > 0)) return 0.0f;
    AccumulateView(row, col, AxisLerp::At(k, n_s_), AxisLerp::At(l, n_t_), held, acc);
    return held;
  }

  // Whether the views have their own windows (reads outside a view's window then add nothing).
  bool view_windows() const { return !offsets_.empty(); }
  // Whether camera (row, col)'s own line toward p_o meets the st-plane inside the sampled domain.
  bool CameraLineMeetsStDomain(int row, int col, const Vec3& p_o) const {
    const Vec3& c = camera_centers_[std::size_t(row) * cols_ + col];
    return MeetsStDomain(c, p_o - c);
  }

  // rgb = acc, renormalised by the weight the reads added when views have their own windows;
  // false when nothing was read.
  bool Normalise(const float acc[3], float weight, float rgb[3]) const {
    const float scale = offsets_.empty() ? 1.0f : weight > 0 ? 1.0f / weight : 0.0f;
    for (int ch = 0; ch < 3; ++ch) rgb[ch] = acc[ch] * scale;
    return offsets_.empty() || weight > 0;
  }

 private:
  // With views in their own windows: (k, l) moved into view (row, col)'s window, and whether it
  // lies there; with shared windows always true, (k, l) unchanged.
  bool InOwnWindow(int row, int col, double& k, double& l) const {
    if (offsets_.empty()) return true;
    const StOffset& o = offsets_[std::size_t(row) * cols_ + col];
    k -= o.k;
    l -= o.l;
    return k >= -0.5 && k <= n_s_ - 0.5 && l >= -0.5 && l <= n_t_ - 0.5;
  }

  template <typename F>
  static void ForNearestCameras(const AxisLerp& c, const AxisLerp& r, F&& visit) {
    const int view_r[2] = {r.i0, r.i1}, view_c[2] = {c.i0, c.i1};
    const float wr[2] = {1.0f - r.w1, r.w1}, wc[2] = {1.0f - c.w1, c.w1};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const float w = wr[a] * wc[b];
        if (w != 0.0f) visit(view_r[a], view_c[b], w);
      }
  }

  // acc += w * (bilinear st lookup in view (row, col)).
  void AccumulateView(int row, int col, const AxisLerp& k, const AxisLerp& l, float w,
                      float acc[3]) const {
    if (srgb8_)
      AccumulateTyped<std::uint8_t>(row, col, k, l, w, acc);
    else
      AccumulateTyped<Eigen::half>(row, col, k, l, w, acc);
  }

  static float Decode(std::uint8_t v, const float* lut) { return lut[v]; }
  static float Decode(Eigen::half v, const float*) { return static_cast<float>(v); }

  template <typename T>
  void AccumulateTyped(int row, int col, const AxisLerp& k, const AxisLerp& l, float w,
                       float acc[3]) const {
    const T* view = reinterpret_cast<const T*>(data_) +
                    (std::size_t(row) * cols_ + std::size_t(col)) * view_samples_;
    const std::size_t o00 = (std::size_t(l.i0) * n_s_ + k.i0) * 3;
    const std::size_t o10 = (std::size_t(l.i0) * n_s_ + k.i1) * 3;
    const std::size_t o01 = (std::size_t(l.i1) * n_s_ + k.i0) * 3;
    const std::size_t o11 = (std::size_t(l.i1) * n_s_ + k.i1) * 3;
    const float wk1 = k.w1, wk0 = 1.0f - k.w1, wl1 = l.w1, wl0 = 1.0f - l.w1;
    const float w00 = w * wk0 * wl0, w10 = w * wk1 * wl0, w01 = w * wk0 * wl1, w11 = w * wk1 * wl1;
    for (int ch = 0; ch < 3; ++ch)
      acc[ch] += w00 * Decode(view[o00 + ch], lut_) + w10 * Decode(view[o10 + ch], lut_) +
                 w01 * Decode(view[o01 + ch], lut_) + w11 * Decode(view[o11 + ch], lut_);
  }

  template <typename T>
  void AccumulateCubicTyped(int row, int col, double k, double l, float w, float acc[3]) const {
    const T* view = reinterpret_cast<const T*>(data_) +
                    (std::size_t(row) * cols_ + std::size_t(col)) * view_samples_;
    k = std::clamp(k, 0.0, double(n_s_ - 1));
    l = std::clamp(l, 0.0, double(n_t_ - 1));
    const int k0 = int(std::floor(k)), l0 = int(std::floor(l));
    const auto wk = KeysCubicWeights(k - k0), wl = KeysCubicWeights(l - l0);
    float sum[3] = {0, 0, 0};  // encoded (8-bit codes) or linear (half floats)
    for (int j = 0; j < 4; ++j) {
      const std::size_t lj = std::size_t(std::clamp(l0 - 1 + j, 0, n_t_ - 1));
      for (int i = 0; i < 4; ++i) {
        const std::size_t o = (lj * n_s_ + std::size_t(std::clamp(k0 - 1 + i, 0, n_s_ - 1))) * 3;
        const float ww = wk[i] * wl[j];
        for (int ch = 0; ch < 3; ++ch) sum[ch] += ww * static_cast<float>(view[o + ch]);
      }
    }
    if constexpr (std::is_same_v<T, std::uint8_t>) {
      const auto& fine = SrgbDecodeFineTable();
      for (int ch = 0; ch < 3; ++ch) acc[ch] += w * SrgbToLinearFine(fine, sum[ch] / 255.0f);
    } else {
      for (int ch = 0; ch < 3; ++ch) acc[ch] += w * sum[ch];
    }
  }

  const std::uint8_t* data_;
  bool srgb8_;
  const float* lut_;
  int rows_, cols_, n_s_, n_t_;
  std::size_t view_samples_;  // channel values per view
  Vec3 p_ca_, n_ca_, u_scaled_, v_scaled_;
  Vec3 st_origin_, n_st_, s_scaled_, t_scaled_;
  double s0_, t0_, s_to_k_, t_to_l_;  // the reference grid
  double u_s0_, u_s1_, u_t0_, u_t1_;  // the sampled domain: the union of the views' windows
  std::vector<Vec3> camera_centers_;  // row-major
  std::vector<StOffset> offsets_;     // each view's window, row-major; empty when shared
};

}  // namespace lfcam
