// SweepViews' preparation (depth/cost_volume.h): the reference and its neighbours loaded at the
// matching resolution, their brightness made the reference's, their channels packed, and how each
// is read at a plane; SweepViews::Sweep is in depth/cost_volume.cpp.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"
#include "lfcam/core/view_filling.h"
#include "lfcam/depth/cost_volume.h"
#include "lfcam/depth/noise_level.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/depth/sweep_reads.h"
#include "lfcam/depth/view_sharpness.h"

namespace lfcam {

namespace {

// The reads the two halves of the sweep share (depth/sweep_reads.h).
using sweep::IsScaledShift;
using sweep::IsShift;
using sweep::kChannels;
using sweep::kHalves;
using sweep::kPacked;
using sweep::kSubArrays;
using sweep::ReadWeights;

// How far from a scale and a shift along each axis a view's homography may be, in samples, to be
// read as one (SweepViews::Homography): a calibrated array's st-plane lies a thousandth of a
// radian or so off the array's plane, and the planes of equal depth (along the array's normal)
// then map a view to the reference a hundredth of a sample off a scale and a shift at the frame's
// corners (the demo's capture: 0.0095 at most), a tenth of what the calibration itself leaves (its
// reprojection error: 0.07 of a camera's pixel there, 0.1-0.3 of an st sample).
constexpr double kScaledShiftError = 1.0 / 32;
// Views noisier than kNoisyViewLevels (NoiseLevel, 8-bit levels; cost_volume.h) are read through
// a Gaussian of kNoisyReadSigma samples (ReadWeights). Clean renders measure about 0.4, the real
// photographs here (a Lytro camera's views, JPEG photographs) 0.5-0.8 (docs/depth.md, "Noisy
// views").
constexpr double kNoisyReadSigma = 1.3;
// Clean views with more than kSharpShare of their texture's power near the sampling limit
// (NearNyquistShare) are read through a Gaussian of kSharpReadSigma samples: Keys' cubic would
// pull the matches towards whole and half samples (docs/depth.md, "Sharp views"; the real
// light fields here measure 0.0055-0.015, renders antialiased by a box over the pixel 0.04).
constexpr double kSharpShare = 0.025;
constexpr double kSharpReadSigma = 0.6;

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

// How many of the views' samples (`sample_mm` apart on the st-plane) one pixel of the camera that
// view (row, col) was built from spans at the st-plane's distance; 0 where the light field
// records no cameras.
double CameraPixelSamples(const LightField& lf, int row, int col, double sample_mm) {
  if (!lf.has_view_cameras() || !(sample_mm > 0)) return 0;
  const auto& camera = lf.measured_poses()[std::size_t(row) * lf.dims().cols + col].intrinsics;
  if (!camera || !(camera->fx > 0)) return 0;
  return lf.slab().separation_mm() / camera->fx / sample_mm;
}

// Scaled sample coordinates <-> full-resolution ones (sample centres at integers).
double ToFull(double x, double scale) { return (x + 0.5) * scale - 0.5; }
double ToScaled(double x, double scale) { return (x + 0.5) / scale - 0.5; }

// The views within reach of (row, col).
std::vector<std::pair<int, int>> ViewsAround(const LightFieldDims& d, int row, int col, int reach) {
  std::vector<std::pair<int, int>> around;
  for (int r = std::max(0, row - reach); r <= std::min(d.rows - 1, row + reach); ++r)
    for (int c = std::max(0, col - reach); c <= std::min(d.cols - 1, col + reach); ++c)
      if (r != row || c != col) around.emplace_back(r, c);
  return around;
}

}  // namespace

SweepGeometry GeometryOf(const LightField& lf, int row, int col, const CostVolumeOptions& options) {
  const auto& d = lf.dims();
  SweepGeometry g;
  const double factor = std::max(1.0, options.scale);
  g.width = factor > 1.0 ? std::max(8, int(std::lround(d.n_s / factor))) : d.n_s;
  g.height = factor > 1.0 ? std::max(8, int(std::lround(d.n_t / factor))) : d.n_t;
  g.scale_x = double(d.n_s) / g.width;
  g.scale_y = double(d.n_t) / g.height;
  const Vec3 center = lf.camera_center(row, col);
  for (const auto& [r, c] : ViewsAround(d, row, col, std::max(1, options.reach))) {
    const double mm = (lf.camera_center(r, c) - center).norm();
    g.farthest_mm = std::max(g.farthest_mm, mm);
    g.nearest_mm = g.nearest_mm > 0 ? std::min(g.nearest_mm, mm) : mm;
  }
  g.st_depth =
      DepthOf(lf.slab(), lf.st_sampling(row, col).Point((d.n_s - 1) / 2.0, (d.n_t - 1) / 2.0)) -
      DepthOf(lf.slab(), center);
  g.sample_mm =
      std::min(lf.st_sampling().ds_mm() * g.scale_x, lf.st_sampling().dt_mm() * g.scale_y);
  g.full_sample_mm = std::min(lf.st_sampling().ds_mm(), lf.st_sampling().dt_mm());
  return g;
}

SweepViews::SweepViews(const LightField& lf, int row, int col, const CostVolumeOptions& options)
    : lf_(lf), options_(options), geometry_(GeometryOf(lf, row, col, options)) {
  const auto& d = lf.dims();
  const int w = geometry_.width, h = geometry_.height;  // the matching resolution
  const std::size_t plane = std::size_t(w) * h;
  // The middle of the frame, where views narrowly apart see the same things.
  const cv::Rect middle(w / 8, h / 8, w - w / 4, h - h / 4);
  cv::Scalar reference_mean;
  if (options.blur_to_cameras) {
    // One blur for every view, from the reference's camera: views matched must be filtered alike.
    const double span = CameraPixelSamples(lf, row, col, geometry_.sample_mm);
    if (span > kFinerThanCameraSamples) camera_blur_sigma_ = kCameraBlurPixels * span;
  }
  const auto load = [&](int r, int c) {
    View v;
    cv::Mat rgb = ViewSrgb8(lf, r, c);
    if (rgb.cols != w || rgb.rows != h) cv::resize(rgb, rgb, {w, h}, 0, 0, cv::INTER_AREA);
    if (r == row && c == col) {
      reference_rgb8_ = rgb;
      if (options.adapt_to_noise) {
        noise_level_ = NoiseLevel(rgb);
        near_nyquist_share_ = NearNyquistShare(rgb);
        if (noise_level_ > kNoisyViewLevels)
          read_sigma_ = kNoisyReadSigma;
        else if (near_nyquist_share_ > kSharpShare)
          read_sigma_ = kSharpReadSigma;
      }
    }
    cv::Mat f, grey, gx, gy;
    rgb.convertTo(f, CV_32F, 1.0 / 255.0);
    if (camera_blur_sigma_ > 0)
      cv::GaussianBlur(f, f, {0, 0}, camera_blur_sigma_, camera_blur_sigma_, cv::BORDER_REPLICATE);
    if (r == row && c == col) {
      reference_mean = cv::mean(f(middle));
    } else if (options.equalise_brightness) {
      const cv::Scalar mean = cv::mean(f(middle));
      cv::Scalar gain;
      for (int i = 0; i < 3; ++i)
        gain[i] = mean[i] > 1e-3 ? std::clamp(reference_mean[i] / mean[i], kMinBrightnessGain,
                                              kMaxBrightnessGain)
                                 : 1.0;
      // Black, or darker over its three channels than a gain can take back: matched by nothing.
      const double brightness = mean[0] + mean[1] + mean[2],
                   reference = reference_mean[0] + reference_mean[1] + reference_mean[2];
      v.too_dark = reference > 1e-3 && brightness * kMaxBrightnessGain < reference;
      cv::multiply(f, gain, f);
    }
    cv::cvtColor(f, grey, cv::COLOR_RGB2GRAY);
    cv::Sobel(grey, gx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0, cv::BORDER_REPLICATE);
    cv::Sobel(grey, gy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0, cv::BORDER_REPLICATE);
    std::vector<cv::Mat> planes;
    cv::split(f, planes);
    planes.push_back(gx);
    planes.push_back(gy);
    if (r == row && c == col) {
      v.channels.resize(plane * kChannels);
      for (int i = 0; i < kChannels; ++i)
        planes[std::size_t(i)].copyTo(cv::Mat(h, w, CV_32FC1, v.channels.data() + i * plane));
    } else {
      v.packed.resize(plane * kChannels);
      for (int i = 0; i < kChannels; ++i)
        planes[std::size_t(i)].convertTo(cv::Mat(h, w, CV_16SC1, v.packed.data() + i * plane),
                                         CV_16S, kPacked[std::size_t(i)]);
    }
    v.center = lf.camera_center(r, c);
    v.sampling = lf.st_sampling(r, c);
    // The half-arrays it belongs to: those whose direction its grid offset lies within 90
    // degrees of; the quarter-arrays: those it lies within 45 degrees of.
    const double along_max = std::hypot(double(c - col), double(r - row));
    for (int g = 0; g < kHalves; ++g) {
      const double a = g * std::numbers::pi / 4;
      const double along = (c - col) * std::cos(a) + (r - row) * std::sin(a);
      if (along > 1e-6) v.sub_arrays |= 1u << g;
      if (along >= along_max * std::cos(std::numbers::pi / 4) - 1e-6)
        v.sub_arrays |= 1u << (g + kHalves);
    }
    return v;
  };
  reference_ = load(row, col);
  // Views the light field filled from their neighbours are no photographs: matched, a blend of
  // their neighbours agrees with no depth. Left out, unless no other view is within reach.
  auto around = ViewsAround(d, row, col, std::max(1, options.reach));
  const std::vector<bool> photographed = PhotographedViews(lf);
  std::vector<std::pair<int, int>> of_photographs;
  for (const auto& [r, c] : around)
    if (photographed[std::size_t(r * d.cols + c)]) of_photographs.emplace_back(r, c);
  if (!of_photographs.empty()) around = std::move(of_photographs);
  views_.resize(around.size());
  tbb::parallel_for(std::size_t(0), around.size(),
                    [&](std::size_t i) { views_[i] = load(around[i].first, around[i].second); });
  // Views too dark to match are left out, unless every view is.
  if (std::any_of(views_.begin(), views_.end(), [](const View& v) { return !v.too_dark; })) {
    std::vector<View> kept;
    for (std::size_t i = 0; i < views_.size(); ++i)
      if (views_[i].too_dark)
        too_dark_.push_back(around[i]);
      else
        kept.push_back(std::move(views_[i]));
    views_ = std::move(kept);
  }
  for (View& v : views_) {
    const auto found = std::find(class_sub_arrays_.begin(), class_sub_arrays_.end(), v.sub_arrays);
    v.view_class = int(found - class_sub_arrays_.begin());
    if (found == class_sub_arrays_.end()) class_sub_arrays_.push_back(v.sub_arrays);
  }
  // The quarter-arrays count where they hold other views than the half-arrays: not at reach 1,
  // where both are the three views on a side or around a corner.
  for (const View& v : views_)
    if ((v.sub_arrays & 0xffu) != (v.sub_arrays >> kHalves)) sub_array_count_ = kSubArrays;
  if (views_.empty())
    throw Error(
        fmt::format("depth needs at least two views; this light field has {}x{}", d.rows, d.cols));
  // The Gaussian read is the shifted views' (ReadWeights); views warped by a homography (an
  // st-plane turned from the array's plane) are read by OpenCV's cubic, which the reference must
  // then match unfiltered.
  for (const View& view : views_)
    if (read_sigma_ > 0 && !IsScaledShift(Homography(view, 2.0 * geometry_.st_depth)))
      read_sigma_ = 0;
  if (read_sigma_ > 0) {
    // The reference as a read at a whole sample sees it: the same kernel's three taps.
    const std::array<float, 4> k = ReadWeights(0.0, read_sigma_);
    const cv::Mat kernel = (cv::Mat_<float>(1, 3) << k[0], k[1], k[2]);
    for (int c = 0; c < kChannels; ++c) {
      cv::Mat channel(h, w, CV_32FC1, reference_.channels.data() + c * plane);
      cv::sepFilter2D(channel, channel, CV_32F, kernel, kernel, cv::Point(-1, -1), 0,
                      cv::BORDER_REPLICATE);
    }
  }
}

cv::Matx33d SweepViews::Homography(const View& view, double depth) const {
  const Slab& slab = lf_.slab();
  const double w = geometry_.width - 1, h = geometry_.height - 1;
  const double scale_x = geometry_.scale_x, scale_y = geometry_.scale_y;
  const cv::Point2f from[4] = {{0, 0}, {float(w), 0}, {0, float(h)}, {float(w), float(h)}};
  cv::Point2f to[4];
  const Vec3& c = reference_.center;
  for (int i = 0; i < 4; ++i) {
    const Vec3 x =
        reference_.sampling.Point(ToFull(from[i].x, scale_x), ToFull(from[i].y, scale_y));
    // P on the reference camera's line through x, at depth D.
    const double lambda = (depth - DepthOf(slab, c)) / (DepthOf(slab, x) - DepthOf(slab, c));
    const Vec3 p = c + lambda * (x - c);
    const auto hit = slab.intersect({view.center, p - view.center});
    if (!hit) throw Error("plane sweep: a view's ray runs parallel to the st-plane");
    to[i] = {float(ToScaled(view.sampling.k_of(hit->s), scale_x)),
             float(ToScaled(view.sampling.l_of(hit->t), scale_y))};
  }
  cv::Matx33d m = cv::getPerspectiveTransform(from, to);
  // Where reference sample (xr, yr) lands in the view, in double precision.
  const auto land = [&](double xr, double yr) {
    const Vec3 x = reference_.sampling.Point(ToFull(xr, scale_x), ToFull(yr, scale_y));
    const double lambda = (depth - DepthOf(slab, c)) / (DepthOf(slab, x) - DepthOf(slab, c));
    const Vec3 p = c + lambda * (x - c);
    const auto hit = slab.intersect({view.center, p - view.center});
    if (!hit) throw Error("plane sweep: a view's ray runs parallel to the st-plane");
    return cv::Point2d(ToScaled(view.sampling.k_of(hit->s), scale_x),
                       ToScaled(view.sampling.l_of(hit->t), scale_y));
  };
  // A shift computed through floats: make it exactly one when it is one to within rounding.
  if (std::abs(m(0, 0) - 1) < 1e-6 && std::abs(m(1, 1) - 1) < 1e-6 && std::abs(m(0, 1)) < 1e-6 &&
      std::abs(m(1, 0)) < 1e-6 && std::abs(m(2, 0)) < 1e-9 && std::abs(m(2, 1)) < 1e-9) {
    // The shift itself in double precision, from the centre's mapping.
    const cv::Point2d middle = land(w / 2, h / 2);
    m = cv::Matx33d::eye();
    m(0, 2) = middle.x - w / 2;
    m(1, 2) = middle.y - h / 2;
    return m;
  }
  // A view whose camera lies nearer to or farther from the st-plane than the reference's (a
  // calibrated array's, a millimetre or two off): a scale and a shift along each axis, made
  // exactly one where it is one to within kScaledShiftError over the frame (the st-plane tilted
  // from the array's plane by a calibration's thousandth of a radian bends it by up to a
  // hundredth of a sample), read by the sweep's own kernel rather than warped whole.
  const cv::Point2d left = land(0, h / 2), right = land(w, h / 2);
  const cv::Point2d top = land(w / 2, 0), bottom = land(w / 2, h);
  const double ax = (right.x - left.x) / w, ay = (bottom.y - top.y) / h;
  double error = 0;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) {
      const double xr = 0.5 * i * w, yr = 0.5 * j * h;
      const cv::Point2d at = land(xr, yr);
      error = std::max(
          {error, std::abs(at.x - (ax * xr + left.x)), std::abs(at.y - (ay * yr + top.y))});
    }
  if (ax > 0 && ay > 0 && error <= kScaledShiftError) {
    m = cv::Matx33d::eye();
    m(0, 0) = ax;
    m(0, 2) = left.x;
    m(1, 1) = ay;
    m(1, 2) = top.y;
  }
  return m;
}

std::optional<std::vector<SweepViews::ReadShift>> SweepViews::ReadShifts() const {
  // Two planes' shifts give the line every plane's lies on (a shift is linear in 1/D): planes
  // half and twice the st-plane's distance away, or, for a view scaled as well (whose homography
  // bends the more, the farther the plane from the st-plane), a fifth nearer and farther.
  std::vector<ReadShift> shifts;
  for (const View& v : views_) {
    double d1 = 0.5 * geometry_.st_depth, d2 = 2.0 * geometry_.st_depth;
    cv::Matx33d m1 = Homography(v, d1), m2 = Homography(v, d2);
    if (!IsScaledShift(m1) || !IsScaledShift(m2)) {
      d1 = 0.8 * geometry_.st_depth, d2 = 1.25 * geometry_.st_depth;
      m1 = Homography(v, d1), m2 = Homography(v, d2);
    }
    if (!IsScaledShift(m1) || !IsScaledShift(m2)) return std::nullopt;
    const cv::Point2d t1(m1(0, 2), m1(1, 2)), t2(m2(0, 2), m2(1, 2));
    const cv::Point2d per_q = (t1 - t2) * (1.0 / (1.0 / d1 - 1.0 / d2));
    // A scaled view's scale, linear in 1/D too (to a few parts in ten million over the planes
    // swept, for cameras millimetres off the reference's plane).
    const cv::Point2d s1(m1(0, 0) - 1, m1(1, 1) - 1), s2(m2(0, 0) - 1, m2(1, 1) - 1);
    const cv::Point2d scale_per_q = (s1 - s2) * (1.0 / (1.0 / d1 - 1.0 / d2));
    shifts.push_back({t1 - per_q * (1.0 / d1), per_q, s1 - scale_per_q * (1.0 / d1), scale_per_q});
  }
  return shifts;
}

std::array<cv::Mat, 3> SweepViews::Colour(int i) const {
  const int w = geometry_.width, h = geometry_.height;
  const std::size_t plane = std::size_t(w) * h;
  std::array<cv::Mat, 3> rgb;
  const std::array<cv::Mat, 3> packed = i < 0 ? std::array<cv::Mat, 3>{} : PackedColour(i);
  for (int c = 0; c < 3; ++c) {
    if (i < 0)
      cv::Mat(h, w, CV_32FC1, const_cast<float*>(reference_.channels.data()) + c * plane)
          .copyTo(rgb[std::size_t(c)]);
    else
      packed[std::size_t(c)].convertTo(rgb[std::size_t(c)], CV_32F, 1.0 / kPackedColour);
  }
  return rgb;
}

std::array<cv::Mat, 3> SweepViews::PackedColour(int i) const {
  const int w = geometry_.width, h = geometry_.height;
  const std::size_t plane = std::size_t(w) * h;
  const View& v = views_.at(std::size_t(i));
  std::array<cv::Mat, 3> rgb;
  for (int c = 0; c < 3; ++c)
    rgb[std::size_t(c)] =
        cv::Mat(h, w, CV_16SC1, const_cast<std::int16_t*>(v.packed.data()) + c * plane);
  return rgb;
}

}  // namespace lfcam
