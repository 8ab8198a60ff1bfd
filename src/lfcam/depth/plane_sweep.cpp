#include "lfcam/depth/plane_sweep.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/edge_filter.hpp>
#include <opencv2/ximgproc/weighted_median_filter.hpp>
#include <vector>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"

namespace lfcam {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kMinLabels = 48, kMaxLabels = 512;
constexpr double kCoarseFactor = 4.0;
constexpr float kConfident = 0.25f;  // confidence above which a sample leads the clean-up

// Which side of the reference a view lies on: its cost only competes with the other side of the
// same axis.
enum Side { kLeft, kRight, kBelow, kAbove, kSides };

// A view's samples as 8-bit sRGB with an opaque alpha (CV_8UC4, row l = st row l). Matching
// compares what people see, so a dark region's noise does not vanish in linear light; the alpha
// tells, after a warp, which samples came from inside the view (255) and which from its border.
cv::Mat ViewSrgba8(const LightField& lf, int row, int col) {
  const auto& d = lf.dims();
  cv::Mat rgb(d.n_t, d.n_s, CV_8UC3);
  if (lf.sample_type() == SampleType::kSrgb8) {
    rgb = cv::Mat(d.n_t, d.n_s, CV_8UC3, const_cast<std::uint8_t*>(lf.view_data(row, col)));
  } else {
    for (int l = 0; l < d.n_t; ++l)
      for (int k = 0; k < d.n_s; ++k) {
        const Eigen::Vector3f c = lf.linear_rgb(row, col, k, l);
        rgb.at<cv::Vec3b>(l, k) = {LinearToSrgb8(c.x()), LinearToSrgb8(c.y()),
                                   LinearToSrgb8(c.z())};
      }
  }
  cv::Mat rgba;
  cv::cvtColor(rgb, rgba, cv::COLOR_RGB2RGBA);
  return rgba;
}

// The views a sweep compares and how their sample grids map to one another.
struct SweepSetup {
  const LightField& lf;
  Vec3 ref_center;
  cv::Mat ref;                        // the reference view (scaled), CV_8UC4
  cv::Mat guide;                      // the same, CV_32FC3 in [0, 1]: the filters' guide
  std::vector<cv::Mat> images;        // the other views (scaled), CV_8UC4
  std::vector<Vec3> centers;          // their cameras' centres
  std::vector<Side> sides;            // where each lies
  StSampling ref_sampling;            // the reference view's window on the st-plane
  std::vector<StSampling> samplings;  // the other views' windows
  double scale_x = 1, scale_y = 1;    // full-resolution samples per scaled sample
  double st_depth = 0;                // D of the st-plane at the view's centre
  double farthest_mm = 0;             // the largest baseline used
  double sample_mm = 0;               // a scaled sample's size on the st-plane (the smaller side)
};

// Scaled sample coordinates <-> full-resolution ones (sample centres at integers).
double ToFull(double x, double scale) { return (x + 0.5) * scale - 0.5; }
double ToScaled(double x, double scale) { return (x + 0.5) / scale - 0.5; }

// The homography taking the reference's (scaled) sample coordinates to view v's, through the
// plane of depth D.
cv::Matx33d PlaneHomography(const SweepSetup& setup, std::size_t v, double depth) {
  const Slab& slab = setup.lf.slab();
  const StSampling& sampling = setup.samplings[v];  // view v's own window
  const double w = setup.ref.cols - 1, h = setup.ref.rows - 1;
  const cv::Point2f from[4] = {{0, 0}, {float(w), 0}, {0, float(h)}, {float(w), float(h)}};
  cv::Point2f to[4];
  for (int i = 0; i < 4; ++i) {
    const Vec3 x = setup.ref_sampling.Point(ToFull(from[i].x, setup.scale_x),
                                            ToFull(from[i].y, setup.scale_y));
    const Vec3& c = setup.ref_center;
    // P on the reference camera's line through x, at depth D.
    const double lambda = (depth - DepthOf(slab, c)) / (DepthOf(slab, x) - DepthOf(slab, c));
    const Vec3 p = c + lambda * (x - c);
    const auto hit = slab.intersect({setup.centers[v], p - setup.centers[v]});
    if (!hit) throw Error("plane sweep: a view's ray runs parallel to the st-plane");
    const double k = sampling.k_of(hit->s), l = sampling.l_of(hit->t);
    to[i] = {float(ToScaled(k, setup.scale_x)), float(ToScaled(l, setup.scale_y))};
  }
  return cv::getPerspectiveTransform(from, to);
}

SweepSetup MakeSetup(const LightField& lf, int row, int col, int reach, double factor) {
  const auto& d = lf.dims();
  SweepSetup setup{lf, lf.camera_center(row, col), {}, {}, {}, {}, {}, {}, {}};
  setup.ref_sampling = lf.st_sampling(row, col);
  const auto load = [&](int r, int c) {
    cv::Mat view = ViewSrgba8(lf, r, c);
    if (factor > 1.0) {
      cv::Mat small;
      cv::resize(view, small,
                 {std::max(8, int(std::lround(d.n_s / factor))),
                  std::max(8, int(std::lround(d.n_t / factor)))},
                 0, 0, cv::INTER_AREA);
      return small;
    }
    return view;
  };
  setup.ref = load(row, col);
  cv::Mat rgb;
  cv::cvtColor(setup.ref, rgb, cv::COLOR_RGBA2RGB);
  rgb.convertTo(setup.guide, CV_32F, 1.0 / 255.0);
  setup.scale_x = double(d.n_s) / setup.ref.cols;
  setup.scale_y = double(d.n_t) / setup.ref.rows;
  const auto add = [&](int r, int c, Side side) {
    setup.images.push_back(load(r, c));
    setup.centers.push_back(lf.camera_center(r, c));
    setup.samplings.push_back(lf.st_sampling(r, c));
    setup.sides.push_back(side);
    setup.farthest_mm =
        std::max(setup.farthest_mm, (setup.centers.back() - setup.ref_center).norm());
  };
  for (int step = 1; step <= reach; ++step) {
    if (col - step >= 0) add(row, col - step, kLeft);
    if (col + step < d.cols) add(row, col + step, kRight);
    if (row - step >= 0) add(row - step, col, kBelow);
    if (row + step < d.rows) add(row + step, col, kAbove);
  }
  if (setup.images.empty())
    throw Error(
        fmt::format("depth needs at least two views; this light field has {}x{}", d.rows, d.cols));
  setup.st_depth =
      DepthOf(lf.slab(), setup.ref_sampling.Point((d.n_s - 1) / 2.0, (d.n_t - 1) / 2.0)) -
      DepthOf(lf.slab(), setup.ref_center);
  const double ds = lf.st_sampling().ds_mm(), dt = lf.st_sampling().dt_mm();
  setup.sample_mm = std::min(ds * setup.scale_x, dt * setup.scale_y);
  return setup;
}

struct SweepResult {
  cv::Mat label;       // CV_32FC1, continuous plane index (NaN: no minimum)
  cv::Mat confidence;  // CV_32FC1
};

// The per-sample cost of one plane: per view truncated colour difference, the better side per
// axis, the axes averaged.
void PlaneCost(const SweepSetup& setup, double depth, double truncation, cv::Mat& cost) {
  const int w = setup.ref.cols, h = setup.ref.rows;
  std::vector<cv::Mat> sum(kSides), count(kSides);
  for (int s = 0; s < kSides; ++s) {
    sum[s] = cv::Mat::zeros(h, w, CV_32FC1);
    count[s] = cv::Mat::zeros(h, w, CV_32FC1);
  }
  cv::Mat warped;
  const float cap = float(truncation), to_unit = 1.0f / (3.0f * 255.0f);
  for (std::size_t v = 0; v < setup.images.size(); ++v) {
    const cv::Matx33d m = PlaneHomography(setup, v, depth);
    // Parallel planes make it affine (a shift and scale): the cheaper warp then.
    if (std::abs(m(2, 0)) < 1e-12 && std::abs(m(2, 1)) < 1e-12 && std::abs(m(2, 2) - 1.0) < 1e-12)
      cv::warpAffine(setup.images[v], warped, cv::Matx23d(m.val), {w, h},
                     cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT,
                     cv::Scalar::all(0));
    else
      cv::warpPerspective(setup.images[v], warped, m, {w, h},
                          cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT,
                          cv::Scalar::all(0));
    const int side = setup.sides[v];
    tbb::parallel_for(0, h, [&](int y) {
      const std::uint8_t* a = setup.ref.ptr<std::uint8_t>(y);
      const std::uint8_t* b = warped.ptr<std::uint8_t>(y);
      float* s = sum[side].ptr<float>(y);
      float* n = count[side].ptr<float>(y);
      for (int x = 0; x < w; ++x) {
        const std::uint8_t* pa = a + 4 * x;
        const std::uint8_t* pb = b + 4 * x;
        if (pb[3] != 255) continue;  // (partly) from outside the view
        const int diff =
            std::abs(pa[0] - pb[0]) + std::abs(pa[1] - pb[1]) + std::abs(pa[2] - pb[2]);
        s[x] += std::min(float(diff) * to_unit, cap);
        n[x] += 1.0f;
      }
    });
  }
  cost.create(h, w, CV_32FC1);
  tbb::parallel_for(0, h, [&](int y) {
    float* out = cost.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      float side_cost[kSides];
      for (int s = 0; s < kSides; ++s) {
        const float n = count[s].ptr<float>(y)[x];
        side_cost[s] = n > 0 ? sum[s].ptr<float>(y)[x] / n : kInf;
      }
      const float horizontal = std::min(side_cost[kLeft], side_cost[kRight]);
      const float vertical = std::min(side_cost[kBelow], side_cost[kAbove]);
      if (horizontal < kInf && vertical < kInf)
        out[x] = 0.5f * (horizontal + vertical);
      else if (horizontal < kInf)
        out[x] = horizontal;
      else if (vertical < kInf)
        out[x] = vertical;
      else
        out[x] = cap;  // no view sees this sample through this plane
    }
  });
}

// Sweeps `labels` planes from q_near to q_far (inverse depths), uniformly in q.
SweepResult Sweep(const SweepSetup& setup, double q_near, double q_far, int labels,
                  const PlaneSweepOptions& options, int radius) {
  const int w = setup.ref.cols, h = setup.ref.rows;
  const auto filter = cv::ximgproc::createGuidedFilter(setup.guide, radius, 1e-4);
  cv::Mat best(h, w, CV_32FC1, cv::Scalar(kInf)), before(h, w, CV_32FC1, cv::Scalar(NAN)),
      after(h, w, CV_32FC1, cv::Scalar(NAN)), sum = cv::Mat::zeros(h, w, CV_32FC1);
  cv::Mat index(h, w, CV_32SC1, cv::Scalar(-1));
  cv::Mat cost, filtered, previous;
  for (int i = 0; i < labels; ++i) {
    const double q = q_near + (q_far - q_near) * i / (labels - 1);
    PlaneCost(setup, 1.0 / q, options.truncation, cost);
    filter->filter(cost, filtered);
    tbb::parallel_for(0, h, [&](int y) {
      const float* c = filtered.ptr<float>(y);
      const float* p = i > 0 ? previous.ptr<float>(y) : nullptr;
      float* b = best.ptr<float>(y);
      float* bf = before.ptr<float>(y);
      float* af = after.ptr<float>(y);
      float* s = sum.ptr<float>(y);
      int* idx = index.ptr<int>(y);
      for (int x = 0; x < w; ++x) {
        s[x] += c[x];
        if (c[x] < b[x]) {
          b[x] = c[x];
          idx[x] = i;
          bf[x] = p ? p[x] : NAN;
          af[x] = NAN;
        } else if (idx[x] == i - 1) {
          af[x] = c[x];
        }
      }
    });
    std::swap(previous, filtered);
  }
  SweepResult result{cv::Mat(h, w, CV_32FC1), cv::Mat(h, w, CV_32FC1)};
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const float b = best.at<float>(y, x), bf = before.at<float>(y, x), af = after.at<float>(y, x);
      float offset = 0.0f;
      const float curvature = bf + af - 2.0f * b;
      if (std::isfinite(bf) && std::isfinite(af) && curvature > 0.0f)
        offset = std::clamp(0.5f * (bf - af) / curvature, -0.5f, 0.5f);
      result.label.at<float>(y, x) = float(index.at<int>(y, x)) + offset;
      // How far the best plane stands out, against an absolute floor (a fifth of the cap): where
      // the views agree on every plane (no texture) the mean is near 0 and so is this.
      // A minimum on the first or last plane is no minimum: the depth may lie beyond the range.
      const int i = index.at<int>(y, x);
      const float mean = sum.at<float>(y, x) / float(labels);
      result.confidence.at<float>(y, x) =
          i <= 0 || i >= labels - 1
              ? 0.0f
              : std::clamp((mean - b) / (mean + 0.2f * float(options.truncation)), 0.0f, 1.0f);
    }
  });
  return result;
}

// The weighted-median clean-up: each label becomes the median of its confident neighbours of
// similar colour.
void RefineEdges(const SweepSetup& setup, const SweepResult& sweep, int radius, cv::Mat& label) {
  cv::Mat guide, mask;
  cv::cvtColor(setup.ref, guide, cv::COLOR_RGBA2RGB);
  cv::compare(sweep.confidence, kConfident, mask, cv::CMP_GE);
  mask.convertTo(mask, CV_8U, 1.0 / 255.0);
  if (cv::countNonZero(mask) == 0) return;
  const cv::Mat filled = label.clone();
  {
    // OpenCV 4.6's weighted median is not safe to run twice at once (two views' maps estimated
    // in parallel crash in it): one at a time.
    static std::mutex one_at_a_time;
    std::lock_guard lock(one_at_a_time);
    cv::ximgproc::weightedMedianFilter(guide, filled, label, radius, 25.5, cv::ximgproc::WMF_EXP,
                                       mask);
  }
  // Where the window held no confident sample the filter has nothing to say: keep the fill.
  cv::Mat near_confident;
  cv::boxFilter(mask, near_confident, CV_32F, {2 * radius + 1, 2 * radius + 1}, {-1, -1}, false);
  filled.copyTo(label, near_confident == 0);
}

// Samples without a confident depth (no texture) take one from the confident ones around them,
// near or far: a push-pull fill over a pyramid of confidence-weighted labels (each level half the
// last; a level's empty samples read the coarser level, interpolated).
void FillUnconfident(const cv::Mat& confidence, cv::Mat& label) {
  cv::Mat weight;
  cv::threshold(confidence, weight, kConfident, 0.0, cv::THRESH_TOZERO);
  if (cv::countNonZero(weight) == 0) return;
  std::vector<cv::Mat> sums{label.mul(weight)}, weights{weight};
  while (std::min(sums.back().cols, sums.back().rows) > 2) {
    cv::Mat s, w;
    const cv::Size half((sums.back().cols + 1) / 2, (sums.back().rows + 1) / 2);
    cv::resize(sums.back(), s, half, 0, 0, cv::INTER_AREA);
    cv::resize(weights.back(), w, half, 0, 0, cv::INTER_AREA);
    sums.push_back(s);
    weights.push_back(w);
  }
  cv::Mat filled;  // the coarser level's labels, every sample known
  for (int level = int(sums.size()) - 1; level >= 0; --level) {
    cv::Mat here(sums[std::size_t(level)].size(), CV_32FC1);
    cv::Mat coarse;
    if (!filled.empty()) cv::resize(filled, coarse, here.size(), 0, 0, cv::INTER_LINEAR);
    for (int y = 0; y < here.rows; ++y)
      for (int x = 0; x < here.cols; ++x) {
        const float w = weights[std::size_t(level)].at<float>(y, x);
        // Known here, or from the coarser level (the coarsest: the mean of all that is known).
        if (w > 1e-3f)
          here.at<float>(y, x) = sums[std::size_t(level)].at<float>(y, x) / w;
        else
          here.at<float>(y, x) = coarse.empty()
                                     ? float(cv::sum(sums[0])[0] / cv::sum(weights[0])[0])
                                     : coarse.at<float>(y, x);
      }
    filled = here;
  }
  filled.copyTo(label, weight == 0);
}

int FilterRadius(const SweepSetup& setup, const PlaneSweepOptions& options) {
  if (options.filter_radius > 0) return options.filter_radius;
  return std::max(2, int(std::lround(std::min(setup.ref.cols, setup.ref.rows) / 160.0)));
}

// Planes a step apart: the farthest view's samples move `step` samples from one to the next.
double PlaneStep(const SweepSetup& setup, double step_samples) {
  return step_samples * setup.sample_mm / (setup.st_depth * setup.farthest_mm);
}

}  // namespace

DepthRange EstimateDepthRange(const LightField& lf, int row, int col,
                              const PlaneSweepOptions& options) {
  const auto& d = lf.dims();
  // A quarter of the resolution, unless the swept depths would then move the farthest view by
  // fewer than 16 coarse samples (small baselines, wide views: an imported data set).
  const SweepSetup full = MakeSetup(lf, row, col, options.reach, 1.0);
  const double shift_samples = 1.95 * full.farthest_mm / full.sample_mm;  // over 0.5 .. 20 H
  const double factor = std::min({kCoarseFactor, shift_samples / 16.0, d.n_s / 16.0, d.n_t / 16.0});
  const SweepSetup setup = factor > 1.0 ? MakeSetup(lf, row, col, options.reach, factor) : full;
  const double q_near = 2.0 / setup.st_depth, q_far = 0.05 / setup.st_depth;
  const int labels =
      std::clamp(int(std::ceil((q_near - q_far) / PlaneStep(setup, options.step_samples))) + 1,
                 kMinLabels, kMaxLabels);
  const SweepResult sweep = Sweep(setup, q_near, q_far, labels, options, 2);
  std::vector<float> confident;
  for (int y = 0; y < sweep.label.rows; ++y)
    for (int x = 0; x < sweep.label.cols; ++x)
      if (sweep.confidence.at<float>(y, x) >= kConfident)
        confident.push_back(sweep.label.at<float>(y, x));
  double lo = 0, hi = labels - 1;  // label indices: near .. far
  if (confident.size() >= 16) {
    std::sort(confident.begin(), confident.end());
    lo = std::max(0.0, confident[confident.size() / 100] - 2.0);
    hi = std::min(double(labels - 1), confident[confident.size() * 99 / 100] + 2.0);
  }
  const auto depth_at = [&](double label) {
    return 1.0 / (q_near + (q_far - q_near) * label / (labels - 1));
  };
  return {depth_at(lo), depth_at(hi)};
}

DepthMap EstimateDepth(const LightField& lf, int row, int col, const PlaneSweepOptions& options) {
  const auto& d = lf.dims();
  if (row < 0 || row >= d.rows || col < 0 || col >= d.cols)
    throw Error(
        fmt::format("view ({}, {}) is outside the {}x{} light field", row, col, d.rows, d.cols));
  const DepthRange range =
      options.range ? *options.range : EstimateDepthRange(lf, row, col, options);
  if (!range.valid())
    throw Error(fmt::format("invalid depth range {} .. {} mm", range.near_mm, range.far_mm));
  const SweepSetup setup = MakeSetup(lf, row, col, options.reach, 1.0);
  const double q_near = 1.0 / range.near_mm, q_far = 1.0 / range.far_mm;
  const int labels =
      std::clamp(int(std::ceil((q_near - q_far) / PlaneStep(setup, options.step_samples))) + 1,
                 kMinLabels, kMaxLabels);
  const int radius = FilterRadius(setup, options);
  const SweepResult sweep = Sweep(setup, q_near, q_far, labels, options, radius);
  cv::Mat label = sweep.label.clone();
  FillUnconfident(sweep.confidence, label);
  if (options.refine_edges)
    RefineEdges(setup, sweep, options.refine_radius > 0 ? options.refine_radius : 2 * radius + 1,
                label);
  DepthMap map;
  map.row = row;
  map.col = col;
  map.range = range;
  map.confidence = sweep.confidence;
  map.depth.create(label.size(), CV_32FC1);
  for (int y = 0; y < label.rows; ++y)
    for (int x = 0; x < label.cols; ++x) {
      const double q = q_near + (q_far - q_near) * label.at<float>(y, x) / (labels - 1);
      map.depth.at<float>(y, x) = float(1.0 / q);
    }
  return map;
}

}  // namespace lfcam
