#include "lfcam/render/depth_aware_sampler.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lfcam/core/error.h"
#include "lfcam/core/view_filling.h"
#include "lfcam/depth/plane_sweep.h"

namespace lfcam {

DepthAwareSampler::DepthAwareSampler(const LightField& lf, const DepthSet& depth,
                                     const LightFieldSampler& colour)
    : colour_(colour),
      slab_(lf.sampled_slab()),
      rows_(lf.dims().rows),
      cols_(lf.dims().cols),
      n_s_(lf.dims().n_s),
      n_t_(lf.dims().n_t) {
  if (!(depth.dims() == lf.dims()))
    throw Error("the depth maps were made for another light field (grid or st resolution differ)");
  // A view filled from its neighbours is no photograph: read as a camera that sees nothing (the
  // others' weights renormalised), whatever map it has.
  const std::vector<bool> photographed = PhotographedViews(lf);
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c) {
      Camera camera;
      camera.center = lf.camera_center(r, c);
      camera.window = lf.st_offset(r, c);
      if (depth.has(r, c) && photographed[std::size_t(r * cols_ + c)]) {
        const cv::Mat& m = depth.at(r, c).depth;
        camera.depth = m.ptr<float>(0);
        camera.stride = m.step1();
      }
      cameras_.push_back(camera);
    }
  const DepthRange range = depth.range();
  if (!range.valid()) throw Error("depth-aware rendering needs depth maps; none were given");
  q_near_ = 1.1 / range.near_mm;
  q_far_ = 0.9 / range.far_mm;
  const StSampling sampling = lf.st_sampling();
  const double ds = sampling.ds_mm(), dt = sampling.dt_mm();
  unit_q_ = std::min(ds, dt) / (slab_.separation_mm() * slab_.uv.pitch_mm);
}

double DepthAwareSampler::tolerance(double q) const { return std::max(unit_q_, 0.015 * q); }

bool DepthAwareSampler::Project(int c, const Vec3& p, double& k, double& l) const {
  return colour_.StSampleAt(cameras_[std::size_t(c)].center, p, k, l);
}

bool DepthAwareSampler::Read(int c, const Vec3& p, double q, float w, float acc[3]) const {
  double k, l;
  if (!Project(c, p, k, l)) return false;
  // Camera c sees p when the sample nearest to p's projection has p's depth.
  const float d = DepthAt(c, k, l);
  if (!(std::isfinite(d) && d > 0.0f && std::abs(1.0 / d - q) <= tolerance(q))) return false;
  if (acc) {
    if (cubic_reads_)
      colour_.AccumulateAtCubic(c / cols_, c % cols_, k, l, w, acc);
    else
      colour_.AccumulateAt(c / cols_, c % cols_, k, l, w, acc);
  }
  return true;
}

double DepthAwareSampler::March(int c, const Vec3& origin, const Vec3& direction) const {
  const Vec3& n = slab_.uv.n_ca;
  const double n_dir = n.dot(direction);
  if (n_dir >= 0.0) return -1.0;  // the ray runs away from the scene
  const double origin_depth = DepthOf(slab_, origin);
  // The ray's point at inverse depth q is origin + ((origin_depth - 1/q) / n_dir) direction:
  // a + (1/q) b, projected into camera c's samples by one precomputed map.
  const auto line =
      colour_.ProjectLine(cameras_[std::size_t(c)].center,
                          origin + (origin_depth / n_dir) * direction, (-1.0 / n_dir) * direction);
  // The range's part in front of the ray's origin.
  const double q_a = std::min(q_near_, 1.0 / (std::max(origin_depth, 0.0) + 1.0)), q_b = q_far_;
  if (!(q_a > q_b)) return -1.0;
  double k_a, l_a, k_b, l_b;
  if (!line.AtReciprocal(q_a, k_a, l_a) || !line.AtReciprocal(q_b, k_b, l_b)) return -1.0;
  const double travel = std::hypot(k_b - k_a, l_b - l_a);
  const int steps =
      std::clamp(int(std::ceil(std::max(2.0 * travel, (q_a - q_b) / unit_q_))), 4, 2048);
  bool have_previous = false;
  double prev_q = 0, prev_g = 0, prev_qc = 0;
  for (int i = 0; i <= steps; ++i) {
    const double q = q_a + (q_b - q_a) * i / steps;
    double k, l;
    const float d = line.AtReciprocal(q, k, l) ? DepthAt(c, k, l) : NAN;
    if (!(std::isfinite(d) && d > 0.0f)) {
      have_previous = false;
      continue;
    }
    const double qc = 1.0 / d, g = q - qc;  // g > 0: the ray's point lies in front of the surface
    if (have_previous) {
      if (prev_g > 0.0 && g <= 0.0 && std::abs(qc - prev_qc) <= 2.0 * tolerance(q))
        return prev_q + (q - prev_q) * prev_g / (prev_g - g);
    } else if (std::abs(g) <= tolerance(q)) {
      return q;  // the march starts on the surface (the edge of a view, or of known depth)
    }
    have_previous = true;
    prev_q = q;
    prev_g = g;
    prev_qc = qc;
  }
  return -1.0;
}

float AgreeingShare(double u, double v) {
  const double du = u - std::round(u), dv = v - std::round(v);
  return float(std::min(1.0, 2.0 * std::hypot(du, dv)));
}

bool DepthAwareSampler::BlendAgreeing(const Vec3& p, double q, double u, double v,
                                      const Neighbour* around, int count, float rgb[3]) const {
  u = std::clamp(u, 0.0, double(cols_ - 1));
  v = std::clamp(v, 0.0, double(rows_ - 1));
  // Every camera within kAgreeingReach steps, read once (the four around among them): at most
  // 5 x 5 cameras, those on the block's edge when (u, v) lies on a camera's row or column with a
  // tent of zero, and skipped.
  const int r_lo = std::max(int(std::ceil(v - kAgreeingReach)), 0);
  const int r_hi = std::min(int(std::floor(v + kAgreeingReach)), rows_ - 1);
  const int c_lo = std::max(int(std::ceil(u - kAgreeingReach)), 0);
  const int c_hi = std::min(int(std::floor(u + kAgreeingReach)), cols_ - 1);
  const int block_cols = c_hi - c_lo + 1;
  constexpr int kMostCells = 25;
  static_assert(kMostCells >= (2 * int(kAgreeingReach) + 1) * (2 * int(kAgreeingReach) + 1),
                "the block holds every camera within kAgreeingReach steps");
  float colour[kMostCells][3];
  double tent[kMostCells];
  bool seen[kMostCells];
  for (int r = r_lo; r <= r_hi; ++r)
    for (int col = c_lo; col <= c_hi; ++col) {
      const int cell = (r - r_lo) * block_cols + (col - c_lo);
      float* one = colour[cell];
      one[0] = one[1] = one[2] = 0.0f;
      tent[cell] =
          (1.0 - std::abs(r - v) / kAgreeingReach) * (1.0 - std::abs(col - u) / kAgreeingReach);
      seen[cell] = tent[cell] > 0.0 && Read(r * cols_ + col, p, q, 1.0f, one);
    }
  // The four's reads, from the block (where they always lie: within a step of (u, v)), else
  // read here; then their blend, and their spread about it, in linear light.
  const float* four[4];
  float spare[4][3];
  float near[3] = {0, 0, 0}, total = 0.0f;
  for (int j = 0; j < count; ++j) {
    const int index = around[j].index, r = index / cols_, col = index % cols_;
    const int cell = (r - r_lo) * block_cols + (col - c_lo);
    if (r >= r_lo && r <= r_hi && col >= c_lo && col <= c_hi && tent[cell] > 0.0) {
      four[j] = seen[cell] ? colour[cell] : nullptr;
    } else {
      spare[j][0] = spare[j][1] = spare[j][2] = 0.0f;
      four[j] = Read(index, p, q, 1.0f, spare[j]) ? spare[j] : nullptr;
    }
    if (!four[j]) continue;
    for (int ch = 0; ch < 3; ++ch) near[ch] += around[j].weight * four[j][ch];
    total += around[j].weight;
  }
  if (!(total > 0.0f)) return false;
  for (int ch = 0; ch < 3; ++ch) rgb[ch] = near[ch] / total;
  const float share = AgreeingShare(u, v);
  if (share <= 0.0f) return true;  // at a camera: its own photograph
  const auto distance2 = [&](const float* one) {
    double d2 = 0.0;
    for (int ch = 0; ch < 3; ++ch) d2 += double(one[ch] - rgb[ch]) * (one[ch] - rgb[ch]);
    return d2;
  };
  double spread = 0.0, held = 0.0;
  for (int j = 0; j < count; ++j)
    if (four[j]) {
      spread += around[j].weight * distance2(four[j]);
      held += around[j].weight;
    }
  const double s2 = kAgreementFloor * kAgreementFloor + (held > 0.0 ? spread / held : 0.0);
  // Each camera that sees p, by its tent and how far its colour lies from the four's.
  double sum[3] = {0, 0, 0}, weight = 0.0;
  for (int cell = 0; cell < (r_hi - r_lo + 1) * block_cols; ++cell) {
    if (!seen[cell]) continue;
    const double w = tent[cell] * std::exp(-0.5 * distance2(colour[cell]) / s2);
    for (int ch = 0; ch < 3; ++ch) sum[ch] += w * colour[cell][ch];
    weight += w;
  }
  if (weight > 0.0)
    for (int ch = 0; ch < 3; ++ch)
      rgb[ch] = (1.0f - share) * rgb[ch] + share * float(sum[ch] / weight);
  return true;
}

bool DepthAwareSampler::Sample(const Vec3& origin, const Vec3& direction, float rgb[3]) const {
  const auto c = slab_.intersect({origin, direction});
  if (!c || !slab_.contains(*c)) return false;
  const AxisLerp col = AxisLerp::At(c->u * cols_ - 0.5, cols_);
  const AxisLerp row = AxisLerp::At(c->v * rows_ - 0.5, rows_);
  Neighbour around[4];
  int count = 0;
  const int rs[2] = {row.i0, row.i1}, cs[2] = {col.i0, col.i1};
  const float wr[2] = {1.0f - row.w1, row.w1}, wc[2] = {1.0f - col.w1, col.w1};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      if (wr[a] * wc[b] > 0.0f) around[count++] = {rs[a] * cols_ + cs[b], wr[a] * wc[b]};

  const double n_dir = slab_.uv.n_ca.dot(direction), origin_depth = DepthOf(slab_, origin);
  const auto point = [&](double q) {
    return Vec3(origin + ((origin_depth - 1.0 / q) / n_dir) * direction);
  };
  // Each camera's hit, put to all of them, the heaviest camera's first; a hit that every camera
  // agrees with is taken at once (the others' marches could only find a point as well supported,
  // nearly always the same one: docs/benchmarks.md, "The depth lookup's search ended at a hit
  // every camera agrees with").
  for (int i = 1; i < count; ++i)
    for (int j = i; j > 0 && around[j].weight > around[j - 1].weight; --j)
      std::swap(around[j], around[j - 1]);
  float all = 0.0f;
  for (int j = 0; j < count; ++j) all += around[j].weight;
  double best_q = -1.0;
  float best_support = 0.0f;
  for (int i = 0; i < count && !(best_support > all - 1e-6f); ++i) {
    const double q = March(around[i].index, origin, direction);
    if (q <= 0.0) continue;
    const Vec3 p = point(q);
    float support = 0.0f;
    for (int j = 0; j < count; ++j)
      if (Read(around[j].index, p, q, 0.0f, nullptr)) support += around[j].weight;
    if (support > best_support + 1e-6f || (support > best_support - 1e-6f && q > best_q)) {
      best_support = support;
      best_q = q;
    }
  }
  if (best_q > 0.0) {
    const Vec3 p = point(best_q);
    if (blend_ == DepthBlend::kAgreeing) {
      if (BlendAgreeing(p, best_q, c->u * cols_ - 0.5, c->v * rows_ - 0.5, around, count, rgb))
        return true;
    } else {
      float acc[3] = {0, 0, 0}, total = 0.0f;
      for (int j = 0; j < count; ++j)
        if (Read(around[j].index, p, best_q, around[j].weight, acc)) total += around[j].weight;
      if (total > 0.0f) {
        for (int ch = 0; ch < 3; ++ch) rgb[ch] = acc[ch] / total;
        return true;
      }
    }
  }
  return colour_.Fetch(c->u, c->v, c->s, c->t, rgb);  // no depth found: the paper's lookup
}

bool DepthLookupReadsCubic(const VirtualCamera& camera, const LightFieldSampler& sampler) {
  // How many st samples one pixel spans at the frame's centre: where the central ray and the ray
  // one pixel across, both from the eye, meet the st-plane.
  const int i = camera.width() / 2, j = camera.height() / 2;
  const Vec3& eye = camera.e_c();
  double k0, l0, k1, l1;
  if (!sampler.StSampleAt(eye, eye + camera.pixel_direction(i, j), k0, l0) ||
      !sampler.StSampleAt(eye, eye + camera.pixel_direction(i + 1, j), k1, l1))
    return false;
  return std::hypot(k1 - k0, l1 - l0) <= kCubicFootprint;
}

std::vector<bool> DepthViewsNeeded(const LightField& lf, const VirtualCamera& camera) {
  const auto& d = lf.dims();
  std::vector<bool> needed(d.view_count(), false);
  const std::vector<bool> photographed = PhotographedViews(lf);  // a filled view is never read
  const Slab slab = lf.sampled_slab();
  const auto mark = [&](const Vec3& origin, const Vec3& direction) {
    const auto c = slab.intersect({origin, direction});
    if (!c || !slab.contains(*c)) return;
    const int col = int(std::floor(c->u * d.cols - 0.5)),
              row = int(std::floor(c->v * d.rows - 0.5));
    for (int r = row - 1; r <= row + 2; ++r)
      for (int k = col - 1; k <= col + 2; ++k)
        if (r >= 0 && r < d.rows && k >= 0 && k < d.cols)
          needed[std::size_t(r) * d.cols + std::size_t(k)] =
              photographed[std::size_t(r) * d.cols + std::size_t(k)];
  };
  std::vector<Vec3> lens;
  for (const Vec2& disk : camera.lens_samples()) lens.push_back(camera.lens_point(disk));
  const auto lattice = [](int n) {
    std::vector<int> at;
    for (int i = 0; i < n; i += 8) at.push_back(i);
    if (at.back() != n - 1) at.push_back(n - 1);
    return at;
  };
  for (int j : lattice(camera.height()))
    for (int i : lattice(camera.width())) {
      const Vec3 direction = camera.pixel_direction(i, j);
      if (camera.is_pinhole()) {
        mark(camera.e_c(), direction);
        continue;
      }
      const Vec3 p_o = camera.focus_point(direction);
      for (const Vec3& x : lens) mark(x, p_o - x);
    }
  return needed;
}

}  // namespace lfcam
