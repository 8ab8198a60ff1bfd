#include "lfcam/render/quadrilinear_limit.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"
#include "lfcam/render/srgb_values.h"
#include "lfcam/render/strided_sums.h"

namespace lfcam {

StPrefilter QuadrilinearLimitPrefilter(const LightField& lf, const VirtualCamera& camera) {
  StPrefilter f;
  if (camera.is_pinhole()) return f;
  const Slab& slab = lf.slab();
  const ViewWindow& st = slab.st;
  const Vec3 normal = st.normal();
  const Vec3 p_o =
      camera.focus_point(camera.direction_through(0.5 * camera.width(), 0.5 * camera.height()));
  const double h_o = normal.dot(p_o - st.origin);
  const double h_uv = normal.dot(slab.uv.p_ca - st.origin);
  if (!(std::abs(h_uv - h_o) > 1e-9)) return f;
  f.k = -h_o / (h_uv - h_o);
  const StSampling sampling = lf.st_sampling();
  f.h_s = std::abs(f.k) * slab.uv.pitch_mm / sampling.ds_mm();
  f.h_t = std::abs(f.k) * slab.uv.pitch_mm / sampling.dt_mm();
  return f;
}

WindowTaper QuadrilinearLimitTaper(const LightField& lf, const LightField& copy,
                                   const StPrefilter& prefilter) {
  WindowTaper taper;
  taper.h_k = prefilter.h_s / prefilter.stride_s;
  taper.h_l = prefilter.h_t / prefilter.stride_t;
  const LightFieldDims& d = lf.dims();
  for (int row = 0; row < d.rows; ++row)
    for (int col = 0; col < d.cols; ++col) {
      // The view's window (its samples' outer edges, in window units) in the copy's own samples.
      const StDomain window = lf.st_sampling(row, col).domain;
      const StSampling in_copy = copy.st_sampling(row, col);
      taper.windows.push_back({float(in_copy.k_of(window.s0)), float(in_copy.l_of(window.t0)),
                               float(in_copy.k_of(window.s1)), float(in_copy.l_of(window.t1))});
    }
  return taper;
}

namespace {

// The tent of half-width w sampled at the integers, normalised, and its variance.
std::vector<double> SampledTent(double w, double* variance) {
  const int n = int(std::ceil(w)) - 1;
  std::vector<double> taps;
  double total = 0, second = 0;
  for (int d = -n; d <= n; ++d) {
    const double v = std::max(0.0, 1.0 - std::abs(d) / w);
    taps.push_back(v);
    total += v;
    second += v * d * d;
  }
  for (double& v : taps) v /= total;
  *variance = second / total;
  return taps;
}

}  // namespace

int PrefilterStride(double h, int samples) {
  // The taps left for a copy kept every m samples are a tent of half-width w with
  // w^2 = h^2 + 1 - m^2 (PrefilterTaps). What the copy aliases is what that tent passes near
  // the copy's Nyquist frequency, 1 / (2m) cycles a sample: none where w >= 2m (the tent's first
  // zero). Natural images hold less there the smaller m is, so strides of 2 and 3 are kept with
  // w >= 1.45 m (measured, docs/benchmarks.md: 54-58 dB from the whole copy's frame on the paper
  // scene's checkerboard and the shop's photographs; 4 and more need w >= 2m, below which the
  // checkerboard's frames fell to 44-49 dB).
  const auto accepted = [&](int m) {
    const double w2 = h * h + 1 - double(m) * m;
    return w2 >= (m <= 3 ? 1.45 * 1.45 : 4.0) * m * m && samples / m >= 16;
  };
  int m = 1;  // every stride below an accepted one is accepted too
  while (accepted(m + 1)) ++m;
  return m;
}

std::vector<float> PrefilterTaps(double h, int stride) {
  // The renderer reads the filtered view bilinearly: a tent of half-width `stride` (view
  // samples) after the taps. For the two to make tent_1 * tent_h, the taps take the rest of its
  // variance, (h^2 + 1 - stride^2) / 6 (the variances of convolved kernels add; with stride 1,
  // tent_h's own h^2 / 6), in the tent's own shape where it is wide enough.
  const double target = (h * h + 1 - double(stride) * stride) / 6;
  if (!(h > 1e-6) || !(target > 1e-12)) return {1.0f};
  std::vector<double> taps;
  if (target <= 1.0 / 3) {
    const double a = target / 2;  // [a, 1 - 2a, a]: variance 2a
    taps = {a, 1 - 2 * a, a};
  } else {
    // The sampled tent's variance grows with its width from 1/3 at 4/3 samples: bisect for it.
    double lo = 4.0 / 3, hi = 2 * h + 2, variance = 0;
    for (int i = 0; i < 100; ++i) {
      const double mid = 0.5 * (lo + hi);
      SampledTent(mid, &variance);
      (variance < target ? lo : hi) = mid;
    }
    taps = SampledTent(0.5 * (lo + hi), &variance);
  }
  return std::vector<float>(taps.begin(), taps.end());
}

std::vector<cv::Rect> ViewRegionsRead(const LightField& lf, const VirtualCamera& camera,
                                      const std::vector<bool>& views) {
  const LightFieldDims& d = lf.dims();
  const Slab& slab = lf.slab();
  const cv::Rect whole(0, 0, d.n_s, d.n_t);
  std::vector<Vec3> focus;  // the frame's corners on the plane of focus
  for (const double y : {0.0, double(camera.height())})
    for (const double x : {0.0, double(camera.width())})
      focus.push_back(camera.focus_point(camera.direction_through(x, y)));
  std::vector<cv::Rect> regions(d.view_count());
  for (int v = 0; v < int(d.view_count()); ++v) {
    if (!views[std::size_t(v)]) continue;
    const Vec3 eye = lf.camera_center(v / d.cols, v % d.cols);
    const StSampling sampling = lf.st_sampling(v / d.cols, v % d.cols);  // the view's own window
    double k0 = 1e300, k1 = -1e300, l0 = 1e300, l1 = -1e300;
    bool all = true;
    for (const Vec3& p : focus) {
      const auto c = slab.intersect({eye, (p - eye).normalized()});
      if (!c || !std::isfinite(c->s) || !std::isfinite(c->t)) {
        all = false;
        break;
      }
      const double k = sampling.k_of(c->s), l = sampling.l_of(c->t);
      k0 = std::min(k0, k), k1 = std::max(k1, k), l0 = std::min(l0, l), l1 = std::max(l1, l);
    }
    if (!all) {
      regions[std::size_t(v)] = whole;
      continue;
    }
    // Two samples of margin: a bilinear read at the edge, and rounding.
    const double lo_k = std::max(-1.0, k0 - 2), hi_k = std::min(double(d.n_s), k1 + 3);
    const double lo_l = std::max(-1.0, l0 - 2), hi_l = std::min(double(d.n_t), l1 + 3);
    const cv::Rect r(int(std::floor(lo_k)), int(std::floor(lo_l)),
                     int(std::ceil(hi_k) - std::floor(lo_k)),
                     int(std::ceil(hi_l) - std::floor(lo_l)));
    regions[std::size_t(v)] = r & whole;
  }
  return regions;
}

namespace {

int FloorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Each thread's linear and filtered samples, kept from view to view (fresh blocks this size
// would each be mapped and faulted in anew).
struct Scratch {
  // Uninitialised floats (three a sample), grown as needed: each view writes what it reads.
  std::unique_ptr<float[]> linear, filtered;
  std::size_t linear_size = 0, filtered_size = 0;
  static float* Reserve(std::unique_ptr<float[]>& buffer, std::size_t& size, std::size_t n) {
    if (size < n) {
      buffer.reset(new float[n]);
      size = n;
    }
    return buffer.get();
  }
};

// View (row, col)'s samples inside `source` in linear light, into `linear` (source's size):
// 8-bit samples by the decoding table, or `computed` (within 4.7e-6 of it).
void DecodeRegion(const LightField& lf, int row, int col, const cv::Rect& source, cv::Mat& linear,
                  bool computed = false) {
  const LightFieldDims& d = lf.dims();
  for (int l = 0; l < source.height; ++l) {
    auto* p = linear.ptr<cv::Vec3f>(l);
    if (lf.sample_type() == SampleType::kSrgb8) {
      const std::uint8_t* in =
          lf.view_data(row, col) + 3 * (std::size_t(source.y + l) * d.n_s + std::size_t(source.x));
      (computed ? DecodeSrgbValuesComputed : DecodeSrgbValues)(in, 3 * std::size_t(source.width),
                                                               &p[0][0]);
    } else {
      for (int k = 0; k < source.width; ++k) {
        const Eigen::Vector3f c = lf.linear_rgb(row, col, source.x + k, source.y + l);
        p[k] = {c.x(), c.y(), c.z()};
      }
    }
  }
}

// Writes `width` linear samples into view (row, col) of `out` from sample (k, l) on.
void EncodeRow(const float* linear, int width, int row, int col, int k, int l, LightField* out) {
  if (out->sample_type() == SampleType::kSrgb8) {
    std::uint8_t* o =
        out->mutable_view_data(row, col) + 3 * (std::size_t(l) * out->dims().n_s + std::size_t(k));
    EncodeSrgbValues(linear, 3 * std::size_t(width), o);
  } else {
    for (int i = 0; i < width; ++i)
      out->set_linear_rgb(row, col, k + i, l,
                          {linear[3 * i], linear[3 * i + 1], linear[3 * i + 2]});
  }
}

}  // namespace

namespace {

LightFieldDims PrefilteredCopyDims(const LightField& lf, int stride_s, int stride_t) {
  if (stride_s < 1 || stride_t < 1)
    throw Error(fmt::format("the prefiltered copy's strides must be positive, not {} x {}",
                            stride_s, stride_t));
  const LightFieldDims& d = lf.dims();
  const bool windows = lf.has_view_windows();
  // Copy sample k stands on the view's sample m k + (m - 1) / 2 (rounded down): at its cell's
  // centre for an odd m, half a sample before it for an even m, whose cells then start half a
  // sample before the view's.
  const auto extent = [&](int n, int m) {
    // Each view's copy starts up to m - 1 samples before its own window (its offset rounded
    // down to the copy's), so with windows it needs that much more to reach the end.
    return (n + (windows ? m - 1 : 0) + (m % 2 == 0 ? 1 : 0) + m - 1) / m;
  };
  LightFieldDims copy = d;
  copy.n_s = extent(d.n_s, stride_s);
  copy.n_t = extent(d.n_t, stride_t);
  return copy;
}

}  // namespace

std::size_t PrefilteredCopyBytes(const LightField& lf, int stride_s, int stride_t) {
  return PrefilteredCopyDims(lf, stride_s, stride_t).samples_per_view() * lf.dims().view_count() *
         3 * BytesPerChannel(lf.sample_type());
}

LightField PrefilteredCopy(const LightField& lf, int stride_s, int stride_t,
                           const SampleBuffer& memory) {
  const LightFieldDims& d = lf.dims();
  const LightFieldDims copy = PrefilteredCopyDims(lf, stride_s, stride_t);
  Slab slab = lf.slab();
  StDomain& domain = slab.st_domain;
  const double ds = domain.s_extent() / d.n_s, dt = domain.t_extent() / d.n_t;
  domain.s0 -= stride_s % 2 == 0 ? 0.5 * ds : 0.0;
  domain.t0 -= stride_t % 2 == 0 ? 0.5 * dt : 0.0;
  domain.s1 = domain.s0 + ds * copy.n_s * stride_s;
  domain.t1 = domain.t0 + dt * copy.n_t * stride_t;
  const std::size_t bytes = PrefilteredCopyBytes(lf, stride_s, stride_t);
  LightField out;
  if (memory.size() >= bytes) {
    // The copy in the memory's first bytes, which it keeps alive.
    auto held = std::make_shared<SampleBuffer>(memory);
    std::uint8_t* data = held->mutable_data();
    out = LightField(copy, lf.sample_type(), slab,
                     SampleBuffer::Wrap(std::move(held), data, bytes, true));
  } else {
    RequireMemory(double(bytes) + 2.0 * 12.0 * double(d.samples_per_view()),
                  "the prefiltered copy of the light field");
    // Zeros that cost nothing until written: only the regions read are (a third of each view on
    // the demo's frames).
    out = LightField(copy, lf.sample_type(), slab);
  }
  out.set_measured_poses(lf.measured_poses());
  if (lf.has_view_windows()) {
    std::vector<StOffset> offsets;
    for (const StOffset& o : lf.st_offsets())
      offsets.push_back({FloorDiv(o.k, stride_s), FloorDiv(o.l, stride_t)});
    out.set_st_offsets(std::move(offsets));
  }
  return out;
}

void PrefilterViews(const LightField& lf, const StPrefilter& prefilter,
                    const std::vector<cv::Rect>& regions, LightField* out) {
  const LightFieldDims& d = lf.dims();
  const int m_s = prefilter.stride_s, m_t = prefilter.stride_t;
  const std::vector<float> taps_s = PrefilterTaps(prefilter.h_s, m_s);
  const std::vector<float> taps_t = PrefilterTaps(prefilter.h_t, m_t);
  const int reach_s = int(taps_s.size()) / 2, reach_t = int(taps_t.size()) / 2;
  const cv::Rect whole(0, 0, d.n_s, d.n_t);
  const cv::Rect copy_whole(0, 0, out->dims().n_s, out->dims().n_t);
  tbb::enumerable_thread_specific<Scratch> scratch;
  if (m_s == 1 && m_t == 1) {
    // Every sample kept: OpenCV's separable filter over each region.
    const cv::Mat kernel_s(1, int(taps_s.size()), CV_32F, const_cast<float*>(taps_s.data()));
    const cv::Mat kernel_t(int(taps_t.size()), 1, CV_32F, const_cast<float*>(taps_t.data()));
    tbb::parallel_for(0, int(d.view_count()), [&](int v) {
      const cv::Rect region = regions[std::size_t(v)] & whole;
      if (region.empty()) return;
      const int row = v / d.cols, col = v % d.cols;
      // The region with the kernel's reach around it, as far as the view goes.
      const cv::Rect source = cv::Rect(region.x - reach_s, region.y - reach_t,
                                       region.width + 2 * reach_s, region.height + 2 * reach_t) &
                              whole;
      Scratch& s = scratch.local();
      // Headers over the buffers: `linear` is a whole matrix to OpenCV, so the filter of its
      // region reads the real samples around the region and replicates only beyond `linear`,
      // which stops short of the reach only at the view's own edges.
      cv::Mat linear(source.height, source.width, CV_32FC3,
                     Scratch::Reserve(s.linear, s.linear_size, 3 * std::size_t(source.area())));
      cv::Mat filtered(
          region.height, region.width, CV_32FC3,
          Scratch::Reserve(s.filtered, s.filtered_size, 3 * std::size_t(region.area())));
      DecodeRegion(lf, row, col, source, linear);
      const cv::Mat inner = linear(region - source.tl());
      cv::sepFilter2D(inner, filtered, CV_32F, kernel_s, kernel_t, cv::Point(-1, -1), 0,
                      cv::BORDER_REPLICATE);
      for (int l = 0; l < region.height; ++l)
        EncodeRow(filtered.ptr<float>(l), region.width, row, col, region.x, region.y + l, out);
    });
    return;
  }
  // Kept every m samples: each kept row is the taps' sum of the view's rows around it, and each
  // kept sample of it the taps' sum along the row, only where a copy sample stands.
  tbb::parallel_for(0, int(d.view_count()), [&](int v) {
    const cv::Rect region = regions[std::size_t(v)] & copy_whole;
    if (region.empty()) return;
    const int row = v / d.cols, col = v % d.cols;
    const StOffset own = lf.st_offset(row, col), copy = out->st_offset(row, col);
    // The view's own sample under copy sample k (l).
    const auto view_k = [&](int k) { return m_s * (k + copy.k) + (m_s - 1) / 2 - own.k; };
    const auto view_l = [&](int l) { return m_t * (l + copy.l) + (m_t - 1) / 2 - own.l; };
    const auto clamp_k = [&](int k) { return std::clamp(k, 0, d.n_s - 1); };
    const auto clamp_l = [&](int l) { return std::clamp(l, 0, d.n_t - 1); };
    const int k0 = clamp_k(view_k(region.x) - reach_s);
    const int k1 = clamp_k(view_k(region.br().x - 1) + reach_s);
    const int l0 = clamp_l(view_l(region.y) - reach_t);
    const int l1 = clamp_l(view_l(region.br().y - 1) + reach_t);
    const cv::Rect source(k0, l0, k1 - k0 + 1, l1 - l0 + 1);
    Scratch& s = scratch.local();
    // The view's rows in linear light, each decoded once, as the kept rows come to them: a ring
    // of the rows the taps span (in cache, where decoding the whole region at once would stream
    // four times its bytes through memory).
    const int ring = int(taps_t.size());
    const std::size_t row_values = 3 * std::size_t(source.width);
    float* linear = Scratch::Reserve(s.linear, s.linear_size, std::size_t(ring) * row_values);
    int decoded = l0;  // the next row to decode
    // A kept row's filtered samples from the first kept sample's first tap to the last's last,
    // with the view's own columns among them (the view's edge repeated beyond it), then the
    // kept samples themselves.
    const int first = view_k(region.x) - reach_s, last = view_k(region.br().x - 1) + reach_s;
    const int lo = std::min(first, k0), hi = std::max(last, k1);
    const std::size_t padded = 3 * std::size_t(hi - lo + 1);
    float* filtered =
        Scratch::Reserve(s.filtered, s.filtered_size, padded + 3 * std::size_t(region.width));
    float* kept = filtered + padded;
    float* inside = filtered + 3 * std::size_t(k0 - lo);
    std::vector<const float*> rows(taps_t.size());
    for (int l = region.y; l < region.br().y; ++l) {
      for (const int last_row = clamp_l(view_l(l) + reach_t); decoded <= last_row; ++decoded) {
        cv::Mat one(1, source.width, CV_32FC3, linear + std::size_t(decoded % ring) * row_values);
        DecodeRegion(lf, row, col, cv::Rect(source.x, decoded, source.width, 1), one, true);
      }
      for (int i = -reach_t; i <= reach_t; ++i)
        rows[std::size_t(i + reach_t)] =
            linear + std::size_t(clamp_l(view_l(l) + i) % ring) * row_values;
      WeightedRowSum(rows.data(), taps_t.data(), int(taps_t.size()), row_values, inside);
      for (int k = lo; k < k0; ++k) std::copy_n(inside, 3, filtered + 3 * (k - lo));
      for (int k = k1 + 1; k <= hi; ++k)
        std::copy_n(inside + 3 * (k1 - k0), 3, filtered + 3 * (k - lo));
      StridedTapSum(filtered + 3 * (first - lo), taps_s.data(), int(taps_s.size()), m_s,
                    std::size_t(region.width), kept);
      EncodeRow(kept, region.width, row, col, region.x, l, out);
    }
  });
}

}  // namespace lfcam
