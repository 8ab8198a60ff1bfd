#include "lfcam/render/quadrilinear_limit.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/limits.h"
#include "lfcam/render/srgb_values.h"

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

std::vector<float> PrefilterTaps(double h) {
  if (!(h > 1e-6)) return {1.0f};
  // The renderer reads the filtered view bilinearly: a tent of half-width 1 after the taps. For
  // the two to make tent_1 * tent_h, the taps take the tent_h's part: its variance, h^2 / 6
  // (the variances of convolved kernels add), in the tent's own shape where it is wide enough.
  const double target = h * h / 6;
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

LightField PrefilterViews(const LightField& lf, const StPrefilter& prefilter,
                          const std::vector<cv::Rect>& regions) {
  const LightFieldDims& d = lf.dims();
  RequireMemory(double(lf.total_bytes()) + 2.0 * 12.0 * double(d.samples_per_view()),
                "the prefiltered copy of the light field");
  // Zeros that cost nothing until written: only the regions read are (a third of each view on
  // the demo's frames).
  LightField out(d, lf.sample_type(), lf.slab());
  out.set_measured_poses(lf.measured_poses());
  out.set_st_offsets(lf.st_offsets());
  const std::vector<float> taps_s = PrefilterTaps(prefilter.h_s);
  const std::vector<float> taps_t = PrefilterTaps(prefilter.h_t);
  const cv::Mat kernel_s(1, int(taps_s.size()), CV_32F, const_cast<float*>(taps_s.data()));
  const cv::Mat kernel_t(int(taps_t.size()), 1, CV_32F, const_cast<float*>(taps_t.data()));
  const int reach_s = int(taps_s.size()) / 2, reach_t = int(taps_t.size()) / 2;
  const cv::Rect whole(0, 0, d.n_s, d.n_t);
  const bool bytes = lf.sample_type() == SampleType::kSrgb8;
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
  tbb::enumerable_thread_specific<Scratch> scratch;
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
    cv::Mat filtered(region.height, region.width, CV_32FC3,
                     Scratch::Reserve(s.filtered, s.filtered_size, 3 * std::size_t(region.area())));
    for (int l = 0; l < source.height; ++l) {
      auto* p = linear.ptr<cv::Vec3f>(l);
      if (bytes) {
        const std::uint8_t* in = lf.view_data(row, col) +
                                 3 * (std::size_t(source.y + l) * d.n_s + std::size_t(source.x));
        DecodeSrgbValues(in, 3 * std::size_t(source.width), &p[0][0]);
      } else {
        for (int k = 0; k < source.width; ++k) {
          const Eigen::Vector3f c = lf.linear_rgb(row, col, source.x + k, source.y + l);
          p[k] = {c.x(), c.y(), c.z()};
        }
      }
    }
    const cv::Mat inner = linear(region - source.tl());
    cv::sepFilter2D(inner, filtered, CV_32F, kernel_s, kernel_t, cv::Point(-1, -1), 0,
                    cv::BORDER_REPLICATE);
    for (int l = 0; l < region.height; ++l) {
      const auto* p = filtered.ptr<cv::Vec3f>(l);
      if (bytes) {
        std::uint8_t* o = out.mutable_view_data(row, col) +
                          3 * (std::size_t(region.y + l) * d.n_s + std::size_t(region.x));
        EncodeSrgbValues(&p[0][0], 3 * std::size_t(region.width), o);
      } else {
        for (int k = 0; k < region.width; ++k)
          out.set_linear_rgb(row, col, region.x + k, region.y + l, {p[k][0], p[k][1], p[k][2]});
      }
    }
  });
  return out;
}

}  // namespace lfcam
