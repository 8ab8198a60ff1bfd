#include "lfcam/depth/cost_volume.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"
#include "lfcam/depth/plane_sweep.h"

namespace lfcam {
namespace {

constexpr int kChannels = 5;  // R, G, B (sRGB, 0 .. 1), the grey level's x and y gradients
constexpr int kHalves = 8;    // half-arrays, their directions 45 degrees apart

// A view's samples as 8-bit sRGB (row l = st row l). Matching compares what people see, so a
// dark region's noise does not vanish in linear light.
cv::Mat ViewSrgb8(const LightField& lf, int row, int col) {
  const auto& d = lf.dims();
  if (lf.sample_type() == SampleType::kSrgb8)
    return cv::Mat(d.n_t, d.n_s, CV_8UC3, const_cast<std::uint8_t*>(lf.view_data(row, col)))
        .clone();
  cv::Mat rgb(d.n_t, d.n_s, CV_8UC3);
  for (int l = 0; l < d.n_t; ++l)
    for (int k = 0; k < d.n_s; ++k) {
      const Eigen::Vector3f c = lf.linear_rgb(row, col, k, l);
      rgb.at<cv::Vec3b>(l, k) = {LinearToSrgb8(c.x()), LinearToSrgb8(c.y()), LinearToSrgb8(c.z())};
    }
  return rgb;
}

// Scaled sample coordinates <-> full-resolution ones (sample centres at integers).
double ToFull(double x, double scale) { return (x + 0.5) * scale - 0.5; }
double ToScaled(double x, double scale) { return (x + 0.5) / scale - 0.5; }

// The cubic convolution kernel's four weights (a = -0.75, OpenCV's) for taps -1, 0, 1, 2 at
// fraction f.
std::array<float, 4> CubicWeights(double f) {
  constexpr double a = -0.75;
  const auto near = [](double x) { return ((a + 2) * x - (a + 3)) * x * x + 1; };
  const auto far = [](double x) { return ((a * x - 5 * a) * x + 8 * a) * x - 4 * a; };
  return {float(far(1 + f)), float(near(f)), float(near(1 - f)), float(far(2 - f))};
}

// dst(x, y) = src(x + tx, y + ty), cubic, the source's edge repeated; `valid` says where
// (x + tx, y + ty) lies inside the source. Planes of w x h floats.
void ShiftCubic(const std::vector<float>& src, int w, int h, double tx, double ty,
                std::vector<float>& across, std::vector<float>& dst, std::vector<float>& valid) {
  const int x0 = int(std::floor(tx)), y0 = int(std::floor(ty));
  const auto wx = CubicWeights(tx - x0), wy = CubicWeights(ty - y0);
  const std::size_t plane = std::size_t(w) * h;
  across.resize(plane * kChannels);
  dst.resize(plane * kChannels);
  // Where all four taps lie inside the row: x + x0 - 1 >= 0 and x + x0 + 2 <= w - 1.
  const int inner_lo = std::clamp(1 - x0, 0, w), inner_hi = std::clamp(w - 2 - x0, 0, w);
  for (int c = 0; c < kChannels; ++c)
    for (int y = 0; y < h; ++y) {
      const float* s = src.data() + c * plane + std::size_t(y) * w;
      float* a = across.data() + c * plane + std::size_t(y) * w;
      const auto edge = [&](int x) {
        float v = 0;
        for (int i = 0; i < 4; ++i) v += wx[i] * s[std::clamp(x + x0 - 1 + i, 0, w - 1)];
        a[x] = v;
      };
      for (int x = 0; x < std::min(inner_lo, w); ++x) edge(x);
      for (int x = inner_lo; x < inner_hi; ++x) {
        const float* p = s + x + x0 - 1;
        a[x] = wx[0] * p[0] + wx[1] * p[1] + wx[2] * p[2] + wx[3] * p[3];
      }
      for (int x = std::max(inner_hi, inner_lo); x < w; ++x) edge(x);
    }
  for (int c = 0; c < kChannels; ++c)
    for (int y = 0; y < h; ++y) {
      const float* r[4];
      for (int j = 0; j < 4; ++j)
        r[j] = across.data() + c * plane + std::size_t(std::clamp(y + y0 - 1 + j, 0, h - 1)) * w;
      float* out = dst.data() + c * plane + std::size_t(y) * w;
      for (int x = 0; x < w; ++x)
        out[x] = wy[0] * r[0][x] + wy[1] * r[1][x] + wy[2] * r[2][x] + wy[3] * r[3][x];
    }
  valid.resize(plane);
  for (int y = 0; y < h; ++y) {
    const bool row_in = y + ty >= -1e-6 && y + ty <= h - 1 + 1e-6;
    for (int x = 0; x < w; ++x)
      valid[std::size_t(y) * w + x] =
          row_in && x + tx >= -1e-6 && x + tx <= w - 1 + 1e-6 ? 1.0f : 0.0f;
  }
}

// The same through a general homography m (reference coordinates -> the view's).
void WarpCubic(const std::vector<float>& src, int w, int h, const cv::Matx33d& m,
               std::vector<float>& dst, std::vector<float>& valid) {
  const std::size_t plane = std::size_t(w) * h;
  dst.resize(plane * kChannels);
  for (int c = 0; c < kChannels; ++c) {
    const cv::Mat in(h, w, CV_32FC1, const_cast<float*>(src.data() + c * plane));
    cv::Mat out(h, w, CV_32FC1, dst.data() + c * plane);
    cv::warpPerspective(in, out, m, {w, h}, cv::INTER_CUBIC | cv::WARP_INVERSE_MAP,
                        cv::BORDER_REPLICATE);
  }
  valid.resize(plane);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const cv::Vec3d p = m * cv::Vec3d(x, y, 1);
      const double u = p[0] / p[2], v = p[1] / p[2];
      valid[std::size_t(y) * w + x] =
          p[2] > 0 && u >= -1e-6 && u <= w - 1 + 1e-6 && v >= -1e-6 && v <= h - 1 + 1e-6 ? 1.0f
                                                                                         : 0.0f;
    }
}

bool IsShift(const cv::Matx33d& m) {
  return std::abs(m(0, 0) - 1) < 1e-9 && std::abs(m(1, 1) - 1) < 1e-9 && std::abs(m(0, 1)) < 1e-9 &&
         std::abs(m(1, 0)) < 1e-9 && std::abs(m(2, 0)) < 1e-12 && std::abs(m(2, 1)) < 1e-12 &&
         std::abs(m(2, 2) - 1) < 1e-12;
}

// Per-thread working memory of one plane's cost.
struct Scratch {
  std::vector<float> across, warped, cost, valid, sum, count;
};

}  // namespace

SweepViews::SweepViews(const LightField& lf, int row, int col, const CostVolumeOptions& options)
    : lf_(lf), options_(options) {
  const auto& d = lf.dims();
  const double factor = std::max(1.0, options.scale);
  width_ = factor > 1.0 ? std::max(8, int(std::lround(d.n_s / factor))) : d.n_s;
  height_ = factor > 1.0 ? std::max(8, int(std::lround(d.n_t / factor))) : d.n_t;
  scale_x_ = double(d.n_s) / width_;
  scale_y_ = double(d.n_t) / height_;
  const std::size_t plane = std::size_t(width_) * height_;
  const auto load = [&](int r, int c) {
    View v;
    cv::Mat rgb = ViewSrgb8(lf, r, c);
    if (rgb.cols != width_ || rgb.rows != height_)
      cv::resize(rgb, rgb, {width_, height_}, 0, 0, cv::INTER_AREA);
    if (r == row && c == col) reference_rgb8_ = rgb;
    cv::Mat f, grey, gx, gy;
    rgb.convertTo(f, CV_32F, 1.0 / 255.0);
    cv::cvtColor(f, grey, cv::COLOR_RGB2GRAY);
    cv::Sobel(grey, gx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0, cv::BORDER_REPLICATE);
    cv::Sobel(grey, gy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0, cv::BORDER_REPLICATE);
    v.channels.resize(plane * kChannels);
    std::vector<cv::Mat> planes;
    for (int i = 0; i < 3; ++i)
      planes.emplace_back(height_, width_, CV_32FC1, v.channels.data() + i * plane);
    cv::split(f, planes);
    gx.copyTo(cv::Mat(height_, width_, CV_32FC1, v.channels.data() + 3 * plane));
    gy.copyTo(cv::Mat(height_, width_, CV_32FC1, v.channels.data() + 4 * plane));
    v.center = lf.camera_center(r, c);
    v.sampling = lf.st_sampling(r, c);
    // The half-arrays it belongs to: those whose direction its grid offset lies within 90
    // degrees of.
    for (int g = 0; g < kHalves; ++g) {
      const double a = g * std::numbers::pi / 4;
      if ((c - col) * std::cos(a) + (r - row) * std::sin(a) > 1e-6) v.halves |= 1u << g;
    }
    return v;
  };
  reference_ = load(row, col);
  const int reach = std::max(1, options.reach);
  for (int r = std::max(0, row - reach); r <= std::min(d.rows - 1, row + reach); ++r)
    for (int c = std::max(0, col - reach); c <= std::min(d.cols - 1, col + reach); ++c) {
      if (r == row && c == col) continue;
      views_.push_back(load(r, c));
      const double mm = (views_.back().center - reference_.center).norm();
      farthest_mm_ = std::max(farthest_mm_, mm);
      nearest_mm_ = nearest_mm_ > 0 ? std::min(nearest_mm_, mm) : mm;
    }
  for (View& v : views_) {
    const auto found = std::find(class_halves_.begin(), class_halves_.end(), v.halves);
    v.view_class = int(found - class_halves_.begin());
    if (found == class_halves_.end()) class_halves_.push_back(v.halves);
  }
  if (views_.empty())
    throw Error(
        fmt::format("depth needs at least two views; this light field has {}x{}", d.rows, d.cols));
  st_depth_ = DepthOf(lf.slab(), reference_.sampling.Point((d.n_s - 1) / 2.0, (d.n_t - 1) / 2.0)) -
              DepthOf(lf.slab(), reference_.center);
  sample_mm_ = std::min(lf.st_sampling().ds_mm() * scale_x_, lf.st_sampling().dt_mm() * scale_y_);
  full_sample_mm_ = std::min(lf.st_sampling().ds_mm(), lf.st_sampling().dt_mm());
}

cv::Matx33d SweepViews::Homography(const View& view, double depth) const {
  const Slab& slab = lf_.slab();
  const double w = width_ - 1, h = height_ - 1;
  const cv::Point2f from[4] = {{0, 0}, {float(w), 0}, {0, float(h)}, {float(w), float(h)}};
  cv::Point2f to[4];
  const Vec3& c = reference_.center;
  for (int i = 0; i < 4; ++i) {
    const Vec3 x =
        reference_.sampling.Point(ToFull(from[i].x, scale_x_), ToFull(from[i].y, scale_y_));
    // P on the reference camera's line through x, at depth D.
    const double lambda = (depth - DepthOf(slab, c)) / (DepthOf(slab, x) - DepthOf(slab, c));
    const Vec3 p = c + lambda * (x - c);
    const auto hit = slab.intersect({view.center, p - view.center});
    if (!hit) throw Error("plane sweep: a view's ray runs parallel to the st-plane");
    to[i] = {float(ToScaled(view.sampling.k_of(hit->s), scale_x_)),
             float(ToScaled(view.sampling.l_of(hit->t), scale_y_))};
  }
  cv::Matx33d m = cv::getPerspectiveTransform(from, to);
  // A shift computed through floats: make it exactly one when it is one to within rounding.
  if (std::abs(m(0, 0) - 1) < 1e-6 && std::abs(m(1, 1) - 1) < 1e-6 && std::abs(m(0, 1)) < 1e-6 &&
      std::abs(m(1, 0)) < 1e-6 && std::abs(m(2, 0)) < 1e-9 && std::abs(m(2, 1)) < 1e-9) {
    // The shift itself in double precision, from the centre's mapping.
    const Vec3 x = reference_.sampling.Point(ToFull(w / 2, scale_x_), ToFull(h / 2, scale_y_));
    const double lambda = (depth - DepthOf(slab, c)) / (DepthOf(slab, x) - DepthOf(slab, c));
    const Vec3 p = c + lambda * (x - c);
    const auto hit = slab.intersect({view.center, p - view.center});
    m = cv::Matx33d::eye();
    m(0, 2) = ToScaled(view.sampling.k_of(hit->s), scale_x_) - w / 2;
    m(1, 2) = ToScaled(view.sampling.l_of(hit->t), scale_y_) - h / 2;
  }
  return m;
}

CostVolume SweepViews::Sweep(const std::vector<double>& q) const {
  const int w = width_, h = height_, n = int(q.size());
  const std::size_t plane = std::size_t(w) * h;
  CostVolume volume;
  volume.width = w;
  volume.height = h;
  volume.labels = n;
  volume.cost.assign(plane * std::size_t(n), 0);
  tbb::enumerable_thread_specific<Scratch> scratches;
  const float color_cap = float(options_.color_cap), gradient_cap = float(options_.gradient_cap);
  const float unit = float(CostVolume::kCostUnit);
  const auto most = std::uint16_t(std::lround((options_.color_cap + options_.gradient_cap) * unit));
  const int radius = std::max(0, options_.window_radius);
  // A half-array counts where at least two of its views see the sample (one alone, the rest
  // cut off by the frame's edge, matches too easily by chance), unless none has two.
  int largest_half = 0;
  for (int g = 0; g < kHalves; ++g) {
    int views = 0;
    for (const View& view : views_) views += view.halves >> g & 1;
    largest_half = std::max(largest_half, views);
  }
  const float min_count =
      float(std::min(2, largest_half) * (2 * radius + 1) * (2 * radius + 1)) - 0.01f;
  tbb::parallel_for(0, n, [&](int i) {
    Scratch& s = scratches.local();
    // Sums per class of views (the views in the same half-arrays), then per half-array.
    const std::size_t classes = class_halves_.size();
    s.sum.assign(plane * std::max<std::size_t>(classes, kHalves), 0.0f);
    s.count.assign(plane * std::max<std::size_t>(classes, kHalves), 0.0f);
    s.cost.resize(plane);
    const double depth = 1.0 / q[std::size_t(i)];
    const float* ref = reference_.channels.data();
    for (const View& view : views_) {
      const cv::Matx33d m = Homography(view, depth);
      if (IsShift(m))
        ShiftCubic(view.channels, w, h, m(0, 2), m(1, 2), s.across, s.warped, s.valid);
      else
        WarpCubic(view.channels, w, h, m, s.warped, s.valid);
      const float* war = s.warped.data();
      const float* valid = s.valid.data();
      float* sum = s.sum.data() + std::size_t(view.view_class) * plane;
      float* count = s.count.data() + std::size_t(view.view_class) * plane;
      for (std::size_t p = 0; p < plane; ++p) {
        const float color = (std::abs(war[p] - ref[p]) + std::abs(war[plane + p] - ref[plane + p]) +
                             std::abs(war[2 * plane + p] - ref[2 * plane + p])) *
                            (1.0f / 3.0f);
        const float gradient = std::abs(war[3 * plane + p] - ref[3 * plane + p]) +
                               std::abs(war[4 * plane + p] - ref[4 * plane + p]);
        sum[p] += valid[p] * (std::min(color, color_cap) + std::min(gradient, gradient_cap));
        count[p] += valid[p];
      }
    }
    // The half-arrays' sums from the classes' (in place of the classes', which are then done
    // with: a class's planes are read before any half-array's at or after its index is written).
    {
      std::vector<float>& half_sum = s.warped;
      std::vector<float>& half_count = s.across;
      half_sum.assign(plane * kHalves, 0.0f);
      half_count.assign(plane * kHalves, 0.0f);
      for (std::size_t k = 0; k < classes; ++k)
        for (int g = 0; g < kHalves; ++g) {
          if (!(class_halves_[k] >> g & 1)) continue;
          const float* cs = s.sum.data() + k * plane;
          const float* cc = s.count.data() + k * plane;
          float* hs = half_sum.data() + std::size_t(g) * plane;
          float* hc = half_count.data() + std::size_t(g) * plane;
          for (std::size_t p = 0; p < plane; ++p) {
            hs[p] += cs[p];
            hc[p] += cc[p];
          }
        }
      std::swap(s.sum, half_sum);
      std::swap(s.count, half_count);
    }
    // Each half-array's mean over the window; the cheapest half-array that sees the sample
    // counts.
    std::vector<float>& best = s.cost;
    best.assign(plane, INFINITY);
    for (int g = 0; g < kHalves; ++g) {
      cv::Mat sum(h, w, CV_32FC1, s.sum.data() + std::size_t(g) * plane);
      cv::Mat count(h, w, CV_32FC1, s.count.data() + std::size_t(g) * plane);
      if (radius > 0) {
        cv::boxFilter(sum, sum, -1, {2 * radius + 1, 2 * radius + 1}, {-1, -1}, false,
                      cv::BORDER_REPLICATE);
        cv::boxFilter(count, count, -1, {2 * radius + 1, 2 * radius + 1}, {-1, -1}, false,
                      cv::BORDER_REPLICATE);
      }
      const float* sp = sum.ptr<float>();
      const float* cp = count.ptr<float>();
      for (std::size_t p = 0; p < plane; ++p)
        if (cp[p] > min_count) best[p] = std::min(best[p], sp[p] / cp[p]);
    }
    std::uint16_t* out = volume.cost.data() + i;
    for (std::size_t p = 0; p < plane; ++p)
      out[p * std::size_t(n)] =
          std::isfinite(best[p]) ? std::uint16_t(std::lround(best[p] * unit)) : most;
  });
  return volume;
}

}  // namespace lfcam
