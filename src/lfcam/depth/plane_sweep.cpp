#include "lfcam/depth/plane_sweep.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/lightfield.h"
#include "lfcam/depth/cost_volume.h"
#include "lfcam/depth/local_planes.h"
#include "lfcam/depth/semi_global.h"
#include "lfcam/depth/silhouette_visibility.h"
#include "lfcam/depth/weighted_median.h"

namespace lfcam {
namespace {

constexpr int kMinLabels = 48, kMaxLabels = 256;
constexpr double kVolumeBytes = 1.2e9;  // the cost volume and its aggregate together, at most
constexpr double kCoarseFactor = 4.0;
constexpr float kConfident = 0.25f;      // confidence above which a sample counts for the range
constexpr double kPopulousShare = 0.02;  // the share of the view's samples that makes a label
                                         // count for the range, unconfident but unique
constexpr int kBroadApart = 4;           // natural planes apart for that uniqueness
// The depth range's coarse sweep: its planes a coarse sample of the farthest view apart (its
// natural planes), at least kFewestCoarseLabels of them; the range's margin beyond the depths
// found, in natural planes.
constexpr int kFewestCoarseLabels = 16;
constexpr double kRangeMarginPlanes = 2.0;
constexpr double kOutlierPixels = 0.4;  // the clean-up's threshold: nearest view's shift, samples
constexpr double kOutlierColourSigma = 25.5;  // the clean-up's colour weight, 8-bit levels
// A dark limb the clean-up keeps lies this far below its surroundings' grey, in 8-bit levels, and
// at least kDarkLimbNoises times the views' noise (docs/depth.md, "Dark limbs kept").
constexpr double kDarkLimbLevels = 4.0, kDarkLimbNoises = 3.0;
// At narrow baselines on views without noise (at most kNoisyViewLevels), the clean-up replaces
// only samples the sweep matched less surely than this: elsewhere the views' evidence stands
// against its colour vote (docs/depth.md, "The clean-up where the sweep was sure").
constexpr float kCleanUpBelowConfidence = 0.05f;
constexpr double kPlaneGapPixels =
    0.3;                              // the plane fit's neighbours: nearest view's shift, samples
constexpr int kWidePlaneRadius = 10;  // the second plane fit's radius, samples
constexpr double kWidePlaneConfidence = 0.1;  // ... for samples less confident than this
constexpr double kSlantPriorSmoothing = 1.5;  // the slant prior's Gaussian, samples
// The map's confidence near a depth edge: within kEdgeReach samples of two neighbouring samples
// whose labels differ by more than kEdgeJumpPixels of the nearest view's shift, it is scaled by
// kEdgeConfidenceScale (a depth edge's place is known to a sample or two: docs/depth.md,
// "Confidence at depth edges").
constexpr double kEdgeJumpPixels = 0.3;
constexpr int kEdgeReach = 2;
constexpr float kEdgeConfidenceScale = 0.25f;

// The matching cost's gradient term's share (SweepViews::Sweep) by how far apart neighbouring
// views see the swept depths, in samples (docs/depth.md, "A sixth round"). Where that range is
// narrow (a dense grid, a plenoptic camera: the views a few samples apart at most), a colour
// difference between the views that is not a shift (vignetting, shading that changes with the
// view) pulls the colour term's minimum off the true disparity by a sizeable part of a sample,
// and the gradients, blind to such smooth differences, lead (Hosni et al.'s 0.89). Where it is
// wide, a slanted surface's texture is foreshortened differently in each view, which changes its
// gradients but not its colours, and the two terms count alike.
constexpr double kNarrowRange = 8.0, kWideRange = 15.0;  // samples between neighbouring views
constexpr double kNarrowGradientShare = 0.89, kWideGradientShare = 0.5;
// Up to as many samples between neighbouring views over the swept depths (the narrow range),
// each view's brightness is also made the reference's (CostVolumeOptions::equalise_brightness).
constexpr double kEqualiseRange = kNarrowRange;
// There too, the silhouettes are re-decided by visibility over a window of 5 samples, up to 10
// passes (elsewhere its defaults: 3 and 3), each depth judged by its own side of the cost's
// window unless the views are noisy. Every narrow rig measured gains from the wider window and
// passes, the thin gaps between near objects most, and all but the slats from the one-sided cost
// (noisy rigs lost by it); on the wide `paper` rig the wider window took a point off its grazing
// table, and the one-sided cost half a point (docs/depth.md, "Visibility at the silhouettes").
// And a depth edge is a jump of 0.35 samples of the nearest view's shift there, not 0.5: a
// surface a third of a pixel in front of another (a chin over a neck) was fattened over it by a
// sample or two that the step never looked at (docs/depth.md, "Small steps").
constexpr int kNarrowVisibilityWindow = 5, kNarrowVisibilityPasses = 10;
constexpr double kNarrowVisibilityEdge = 0.35;

double GradientShare(double neighbour_range) {
  const double t =
      std::clamp((neighbour_range - kNarrowRange) / (kWideRange - kNarrowRange), 0.0, 1.0);
  return kNarrowGradientShare + (kWideGradientShare - kNarrowGradientShare) * t;
}

CostVolumeOptions VolumeOptions(const PlaneSweepOptions& options, double scale) {
  CostVolumeOptions o;
  o.reach = options.reach > 0 ? options.reach : 4;
  o.color_cap = o.gradient_cap = options.truncation;
  o.window_radius = options.window_radius;
  o.scale = scale;
  return o;
}

// The most planes a sweep of `samples` samples may have: the label and memory budgets.
int MostLabels(int samples, int fewest) {
  return std::clamp(int(kVolumeBytes / (4.0 * samples)), fewest, kMaxLabels);
}

// Planes from q_near to q_far (inverse depths), `step` apart or closer, within the label and
// memory budgets.
std::vector<double> Planes(double q_near, double q_far, double step, int samples,
                           int fewest = kMinLabels) {
  const int most = MostLabels(samples, fewest);
  const int n = std::clamp(int(std::ceil((q_near - q_far) / step)) + 1, fewest, most);
  std::vector<double> q(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) q[std::size_t(i)] = q_near + (q_far - q_near) * i / (n - 1);
  return q;
}

// The same, each plane half a spacing and a whole number of spacings from `anchor` (the
// st-plane's inverse depth, where no view moves), within the range, `step` apart (a whole
// multiple of it where the label budget asks). So that the same views swept over ranges a little
// apart (a range found in other units: an imported rig's zero-disparity plane in metres or in
// assumed units) are swept at the same planes and give the same map; and no plane lies where
// every view is read at its own samples, which sharply sampled views match better than a plane
// read between samples by that alone. A range of fewer than kMinLabels natural planes is swept as
// before, its planes closer together (docs/depth.md, "The planes on one lattice").
std::vector<double> AnchoredPlanes(double q_near, double q_far, double step, int samples,
                                   double anchor) {
  if (!std::isfinite(anchor) || !(step > 0)) return Planes(q_near, q_far, step, samples);
  const int most = MostLabels(samples, kMinLabels);
  double spacing = step, k_near = 0;
  const auto count = [&] {
    k_near = std::floor((q_near - anchor) / spacing - 0.5 + 1e-9);
    return int(k_near - std::ceil((q_far - anchor) / spacing - 0.5 - 1e-9)) + 1;
  };
  for (int m = 2; count() > most; ++m) spacing = step * m;
  const int n = count();
  if (n < kMinLabels) return Planes(q_near, q_far, step, samples);
  std::vector<double> q(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) q[std::size_t(i)] = anchor + (k_near - i + 0.5) * spacing;
  return q;
}

struct Choice {
  cv::Mat label;       // CV_32FC1, continuous plane index
  cv::Mat confidence;  // CV_32FC1
  cv::Mat unique;      // CV_32FC1: the uniqueness term of the confidence alone
};

// Per sample: the plane `decide` is cheapest on, refined by a parabola through its neighbours;
// confidence from the matching cost `match` (which may be the same volume): the smaller of how
// far the chosen plane's cost lies below the mean (1 - best / mean, against a floor) and how
// unique it is (how far the cheapest plane more than `apart` planes away lies above it, against
// the depth of the minimum): a repeating texture that matches at two depths is not
// confident, however well it matches.
Choice Choose(const CostVolume& decide, const CostVolume& match, double truncation, int apart) {
  const int w = decide.width, h = decide.height, n = decide.labels;
  Choice out{cv::Mat(h, w, CV_32FC1), cv::Mat(h, w, CV_32FC1), cv::Mat(h, w, CV_32FC1)};
  const float floor = float(0.2 * truncation * CostVolume::kCostUnit);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::uint16_t* s = decide.at(x, y);
      // The first label of the least cost (as std::min_element, in two loops that vectorise).
      std::uint16_t least = std::numeric_limits<std::uint16_t>::max();
      for (int j = 0; j < n; ++j) least = std::min(least, s[j]);
      int i = 0;
      while (s[i] != least) ++i;
      float offset = 0.0f;
      if (i > 0 && i < n - 1) {
        const float a = s[i - 1], b = s[i], c = s[i + 1], curvature = a + c - 2.0f * b;
        if (curvature > 0.0f) offset = std::clamp(0.5f * (a - c) / curvature, -0.5f, 0.5f);
      }
      out.label.at<float>(y, x) = float(i) + offset;
      const std::uint16_t* m = match.at(x, y);
      // The sum in integers (exact, as the double it was), the least cost more than `apart`
      // labels from i on either side: loops without a branch, that vectorise.
      std::uint64_t sum = 0;
      for (int j = 0; j < n; ++j) sum += m[j];
      int second = std::numeric_limits<int>::max();
      for (int j = 0; j < i - apart; ++j) second = std::min<int>(second, m[j]);
      for (int j = std::max(0, i + apart + 1); j < n; ++j) second = std::min<int>(second, m[j]);
      const float mean = float(double(sum) / n), best = m[i];
      const float peak = std::clamp((mean - best) / (mean + floor), 0.0f, 1.0f);
      const float unique =
          second == std::numeric_limits<int>::max()
              ? 1.0f
              : std::clamp((float(second) - best) / ((mean - best) + 1.0f), 0.0f, 1.0f);
      const bool inside = i > 0 && i < n - 1;
      out.confidence.at<float>(y, x) = inside ? std::min(peak, unique) : 0.0f;
      out.unique.at<float>(y, x) = inside ? unique : 0.0f;
    }
  });
  return out;
}

// The disparities (px between neighbouring views, {farthest <= 0, nearest >= 0}) within which
// the import found the views' scene (a rectified rig's `import.scene_disparity_px`,
// docs/format.md); nullopt where the file records none.
std::optional<std::array<double, 2>> RecordedSceneDisparity(const LightField& lf) {
  const nlohmann::json& m = lf.metadata();
  if (!m.is_object() || !m.contains("import") || !m["import"].is_object() ||
      !m["import"].contains("scene_disparity_px"))
    return std::nullopt;
  const nlohmann::json& s = m["import"]["scene_disparity_px"];
  if (!s.is_array() || s.size() != 2 || !s[0].is_number() || !s[1].is_number() ||
      !(s[0].get<double>() <= 0) || !(s[1].get<double>() >= 0) ||
      !(s[1].get<double>() - s[0].get<double>() > 0) ||
      !std::isfinite(s[1].get<double>() - s[0].get<double>()))
    throw Error(fmt::format(
        "the light field's metadata import.scene_disparity_px is {}: not [farthest <= 0, "
        "nearest >= 0] px of disparity between neighbouring views",
        s.dump()));
  return std::array{s[0].get<double>(), s[1].get<double>()};
}

// EstimateDepthRange within the bracket of inverse depths near_factor .. far_factor over the
// st-plane's distance; `room` is how far the depths found lie from the bracket's near end and
// from its far end, in natural planes.
DepthRange RangeWithinBracket(const LightField& lf, int row, int col,
                              const PlaneSweepOptions& options, double near_factor,
                              double far_factor, std::array<double, 2>& room) {
  const auto& d = lf.dims();
  // A quarter of the resolution, unless the swept depths would then move the farthest view by
  // fewer than 16 coarse samples (small baselines, wide views: an imported data set).
  // At least reach 4 whatever the map's own reach: with fewer views a repeating texture matches
  // at a false depth too (the `paper` scene's checkerboard at 1.85 m with reach 2 or 3; the
  // range then spans planes no map needs, and reach 2's `--all` lost 9 points within 1%).
  PlaneSweepOptions wide = options;
  wide.reach = std::max(4, options.reach);
  // Each view's brightness made the reference's here whatever the baseline: a range misled by
  // a brightness step between views cuts off the scene's nearest or farthest surfaces (the
  // `paper` scene 2 mm apart, its corner views 10% darker: BadPix0.07 18.5% with the final sweep
  // alone equalised), while a few per cent of false gain where wide-apart views see different
  // things barely moves where the confident depths lie.
  const auto coarse_options = [&](double factor) {
    CostVolumeOptions o = VolumeOptions(wide, factor);
    o.equalise_brightness = true;
    return o;
  };
  const SweepGeometry full = GeometryOf(lf, row, col, coarse_options(1.0));
  // The farthest view's shift over the bracket, in full-resolution samples.
  const double shift_samples = (near_factor - far_factor) * full.farthest_mm / full.full_sample_mm;
  const double factor = std::min({kCoarseFactor, shift_samples / 16.0, d.n_s / 16.0, d.n_t / 16.0});
  const SweepViews coarse(lf, row, col, coarse_options(std::max(1.0, factor)));
  const double q_near = near_factor / coarse.st_depth(), q_far = far_factor / coarse.st_depth();
  const std::vector<double> q = Planes(q_near, q_far, 1.0 / coarse.farthest_shift_per_q(),
                                       coarse.width() * coarse.height(), kFewestCoarseLabels);
  const CostVolume volume = coarse.Sweep(q, 0.5, options.engine);
  const int labels = int(q.size());
  // A bracket of few natural planes (a coarse sample of the farthest view apart) is swept with
  // kFewestCoarseLabels, closer together. What the range is found from is counted in natural planes
  // all the same (the uniqueness's distances, the margin), so that the range is the same in the
  // views' own samples whatever units the light field is in (an imported rig's zero-disparity
  // plane in metres or in assumed units).
  const double natural_planes = (q_near - q_far) * coarse.farthest_shift_per_q();
  const double per_natural = natural_planes > 0 ? (labels - 1) / natural_planes : 1.0;  // planes
  const auto planes = [&](double natural) {
    return std::max(1, int(std::lround(natural * per_natural)));
  };
  // The matching cost alone decides here (no semi-global step: it would spread a repeating
  // texture's false match over a whole region), and only unique minima count.
  const Choice choice = Choose(volume, volume, options.truncation, planes(1));
  // Uniqueness beyond kBroadApart natural planes: a faint texture's minimum is shallow and wide,
  // but single; a repeating texture's is not.
  const Choice broad = Choose(volume, volume, options.truncation, planes(kBroadApart));
  std::vector<float> confident;
  for (int y = 0; y < choice.label.rows; ++y)
    for (int x = 0; x < choice.label.cols; ++x)
      if (choice.confidence.at<float>(y, x) >= kConfident)
        confident.push_back(choice.label.at<float>(y, x));
  // Label indices, near .. far: where the scene was found, then with the margin.
  double found_lo = 0, found_hi = labels - 1;
  if (confident.size() >= 16) {
    std::sort(confident.begin(), confident.end());
    found_lo = confident[confident.size() / 100];
    found_hi = confident[confident.size() * 99 / 100];
    // A surface of faint texture (the `paper` scene's back wall seen from cameras 3.5 mm apart:
    // confidence about 0.13 all over) is seldom confident, but its samples agree on one label,
    // and that label is a single minimum when looked at broadly: a depth that kPopulousShare of
    // the view's samples choose (counted in bins a natural plane wide), each with a unique
    // minimum beyond kBroadApart natural planes, is in the range. (A repeating texture's false
    // match is populous too, but not unique.)
    const int bins = int(std::floor((labels - 1) / per_natural)) + 1;
    std::vector<int> votes(std::size_t(bins), 0);
    std::vector<double> sum(std::size_t(bins), 0.0);  // of the labels voted for: a bin's mean
    for (int y = 0; y < choice.label.rows; ++y)
      for (int x = 0; x < choice.label.cols; ++x)
        if (broad.unique.at<float>(y, x) >= kConfident) {
          const float label = choice.label.at<float>(y, x);
          const auto i =
              std::size_t(std::clamp(int(std::lround(label / per_natural)), 0, bins - 1));
          ++votes[i];
          sum[i] += label;
        }
    const double enough = kPopulousShare * double(choice.label.total());
    for (std::size_t i = 0; i < votes.size(); ++i)
      if (votes[i] > 0 && votes[i] >= enough) {
        found_lo = std::min(found_lo, sum[i] / votes[i]);
        found_hi = std::max(found_hi, sum[i] / votes[i]);
      }
  }
  const double margin = kRangeMarginPlanes * per_natural;
  room = {found_lo / per_natural, (labels - 1 - found_hi) / per_natural};
  const double lo = std::max(0.0, found_lo - margin);
  const double hi = std::min(double(labels - 1), found_hi + margin);
  const auto depth_at = [&](double label) {
    return 1.0 / (q_near + (q_far - q_near) * std::clamp(label, 0.0, labels - 1.0) / (labels - 1));
  };
  return {depth_at(lo), depth_at(hi), depth_at(found_lo), depth_at(found_hi)};
}

}  // namespace

DepthRange EstimateDepthRange(const LightField& lf, int row, int col,
                              const PlaneSweepOptions& options) {
  // The bracket swept, in inverse depth times the st-plane's distance: 2 to 0.05 (half to twenty
  // times that distance), narrowed to where the import found the scene where it recorded that
  // (a rectified rig: twice the parallax its views show), so that the bracket is the same in the
  // views' own samples whatever the units or wherever infinity lies (a parameters.cfg's metric
  // geometry puts infinity 16-40 px behind a scene of +-2 px, and a sweep of that many px
  // reaches the false depths where a repeating texture matches again; docs/depth.md).
  constexpr double kNearest = 2.0, kFarthest = 0.05;
  // How near the bracket may reach where the scene does: an eighth of the st-plane's distance.
  constexpr double kNearestEver = 8.0;
  // Infinity's disparity between neighbours relative to the st-plane, px: the bracket's ends in
  // px are extents of it.
  const SweepGeometry full = GeometryOf(lf, row, col, VolumeOptions(options, 1.0));
  const double infinity_px = lf.slab().uv.pitch_mm / full.full_sample_mm;
  const auto near_of = [&](double px) { return std::min(kNearestEver, 1.0 + px / infinity_px); };
  const auto far_of = [&](double px) { return std::max(kFarthest, 1.0 - px / infinity_px); };
  const auto twice = [](double px) { return std::max(2 * px, px + 1); };  // a px more at least
  const auto scene = RecordedSceneDisparity(lf);
  double near_factor = scene ? near_of((*scene)[1]) : kNearest;
  double far_factor = scene ? far_of(-(*scene)[0]) : kFarthest;
  // The scene reaching farther than the bracket: an end the record narrowed, where the depths
  // found come so near it that it cuts the range's margin short (a surface the views' tracked
  // points missed), or the near end at or past half the st-plane's distance, where they lie
  // within a natural plane of it (a scene nearer than that: an import's estimate puts the plane
  // at the scene's middle distance). That end then reaches twice as far in px, and again, up to
  // half to twenty times the st-plane's distance, an eighth of it nearer.
  for (;;) {
    std::array<double, 2> room{};
    const DepthRange range =
        RangeWithinBracket(lf, row, col, options, near_factor, far_factor, room);
    const bool near_reached =
        near_factor < kNearestEver && room[0] < (near_factor < kNearest ? kRangeMarginPlanes : 1.0);
    const bool far_reached = far_factor > kFarthest && room[1] < kRangeMarginPlanes;
    if (!near_reached && !far_reached) return range;
    if (near_reached) near_factor = near_of(twice((near_factor - 1.0) * infinity_px));
    if (far_reached) far_factor = far_of(twice((1.0 - far_factor) * infinity_px));
  }
}

namespace {

// Scales the confidence of every sample within kEdgeReach of a depth edge (two neighbouring
// samples whose labels differ by more than `jump_labels`) by kEdgeConfidenceScale: the clear
// cost minimum a silhouette's strong contrast gives says little about which side of the edge a
// sample lies on.
void LessConfidentNearDepthEdges(const cv::Mat& label, double jump_labels, cv::Mat& confidence) {
  cv::Mat edge = cv::Mat::zeros(label.size(), CV_8UC1);
  for (int y = 0; y < label.rows; ++y)
    for (int x = 0; x < label.cols; ++x) {
      const float here = label.at<float>(y, x);
      if (x + 1 < label.cols && std::abs(label.at<float>(y, x + 1) - here) > jump_labels)
        edge.at<std::uint8_t>(y, x) = edge.at<std::uint8_t>(y, x + 1) = 255;
      if (y + 1 < label.rows && std::abs(label.at<float>(y + 1, x) - here) > jump_labels)
        edge.at<std::uint8_t>(y, x) = edge.at<std::uint8_t>(y + 1, x) = 255;
    }
  cv::dilate(edge, edge, cv::Mat::ones(2 * kEdgeReach + 1, 2 * kEdgeReach + 1, CV_8UC1));
  for (int y = 0; y < label.rows; ++y)
    for (int x = 0; x < label.cols; ++x)
      if (edge.at<std::uint8_t>(y, x)) confidence.at<float>(y, x) *= kEdgeConfidenceScale;
}

}  // namespace

bool SeesTheSceneNarrowly(const LightField& lf, int row, int col, const DepthRange& range) {
  const double scene_q = 1.0 / range.scene_near_mm() - 1.0 / range.scene_far_mm();
  CostVolumeOptions one_step;
  one_step.reach = 1;  // the nearest view is a neighbour at any reach
  return scene_q * GeometryOf(lf, row, col, one_step).nearest_shift_per_q() <= kEqualiseRange;
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
  CostVolumeOptions volume_options = VolumeOptions(options, 1.0);
  // Every plane over the same views near the frame's edges; where that leaves no half-array two
  // views (at reach 1, `--all`'s, 3 views a half-array), a pair of opposite half-arrays counts
  // (docs/depth.md, "The frame's edges").
  volume_options.same_views_at_every_plane = true;
  volume_options.adapt_to_noise = true;
  volume_options.blur_to_cameras = options.blur_to_cameras;
  const double q_near = 1.0 / range.near_mm, q_far = 1.0 / range.far_mm;
  // The scene's span in inverse depth, without the margin the range adds to it: how far apart
  // neighbouring views see the scene decides how the views are matched (below).
  const double scene_q = 1.0 / range.scene_near_mm() - 1.0 / range.scene_far_mm();
  // Views narrowly apart see the same things: their brightness is made the reference's.
  const bool narrow = SeesTheSceneNarrowly(lf, row, col, range);
  volume_options.equalise_brightness = narrow;
  const SweepViews views(lf, row, col, volume_options);
  const std::vector<double> q =
      AnchoredPlanes(q_near, q_far, options.step_samples / views.farthest_shift_per_q(),
                     views.width() * views.height(), 1.0 / views.st_depth());
  const int labels = int(q.size());
  const CostVolume volume =
      views.Sweep(q, GradientShare(scene_q * views.nearest_shift_per_q()), options.engine);
  cv::Mat grey;
  cv::cvtColor(views.reference_rgb8(), grey, cv::COLOR_RGB2GRAY);
  // The nearest view's shift a plane, in samples.
  const double per_plane = (q.front() - q.back()) / (labels - 1) * views.nearest_shift_per_q();
  cv::Mat slopes;
  const double dark_limb_levels = std::max(kDarkLimbLevels, kDarkLimbNoises * views.noise_level());
  // `kept`: where the caller keeps the labels (CV_8UC1, or empty: everywhere); the wide plane fit
  // refits nowhere else.
  const auto estimate = [&](const cv::Mat& expected_step, const cv::Mat& kept) {
    const CostVolume aggregate = AggregateSemiGlobal(
        volume, grey, {options.smoothness_p1, options.smoothness_p2}, expected_step);
    // Unique: no other minimum a sample of the farthest view's shift away or more (the whole
    // planes that span at least a sample: 4 at the default spacing of 0.3; docs/depth.md).
    Choice choice = Choose(aggregate, volume, options.truncation,
                           std::max(1, int(std::ceil(1.0 / options.step_samples - 1e-9))));
    if (options.refine_edges) {
      // The threshold: kOutlierPixels of the nearest view's shift, in planes.
      const int radius = options.refine_radius > 0
                             ? options.refine_radius
                             : std::max(2, int(std::lround(std::min(d.n_s, d.n_t) / 70.0)));
      // Outliers: a sample more than the threshold from the weighted median of its neighbours
      // of similar colour (led by the reference view) takes that median.
      WeightedMedianOptions clean_up;
      clean_up.radius = radius;
      clean_up.sigma_levels = kOutlierColourSigma;
      clean_up.threshold = std::max(2.0, kOutlierPixels / per_plane);
      if (options.keep_dark_limbs && narrow) clean_up.dark_limb_levels = dark_limb_levels;
      if (narrow && views.noise_level() <= kNoisyViewLevels)
        clean_up.replace_only = choice.confidence < kCleanUpBelowConfidence;
      ReplaceOutliersByWeightedMedian(views.reference_rgb8(), clean_up, choice.label);
    }
    if (options.fit_local_planes) {
      LocalPlaneOptions fit;
      fit.max_label_gap = kPlaneGapPixels / per_plane;
      choice.label =
          FitLocalPlanes(choice.label, views.reference_rgb8(), choice.confidence, fit, &slopes);
      // Where the views barely tell the planes apart (weak texture: semi-global matching's
      // fill, which wanders about a slanted surface), a plane through twice the neighbourhood.
      fit.radius = kWidePlaneRadius;
      fit.sigma_space = kWidePlaneRadius / 2.0;
      fit.refit_below_confidence = kWidePlaneConfidence;
      fit.refit_only = kept;
      choice.label =
          FitLocalPlanes(choice.label, views.reference_rgb8(), choice.confidence, fit, &slopes);
    }
    return choice;
  };
  Choice choice = estimate(cv::Mat(), cv::Mat());
  if (options.slant_prior && options.fit_local_planes && volume_options.reach >= 2) {
    // Semi-global matching again, its paths expecting the slant of the planes just fitted
    // (smoothed): the first pass's small-step penalty favours surfaces parallel to the array.
    // Kept where the first pass was sure of its match; elsewhere the slopes are its fill's.
    cv::Mat expected_step;
    cv::GaussianBlur(slopes, expected_step, cv::Size(0, 0), kSlantPriorSmoothing);
    // (The second pass's wide plane fit, for its unsure samples, is kept only where the first
    // pass was sure: refitted there alone, the same labels in a fraction of the time.)
    const cv::Mat kept = choice.confidence >= kWidePlaneConfidence;
    const Choice second = estimate(expected_step, kept);
    second.label.copyTo(choice.label, kept);
  }
  if (options.silhouette_visibility) {
    SilhouetteVisibilityOptions visibility;
    if (narrow) {
      visibility.window = kNarrowVisibilityWindow;
      visibility.passes = kNarrowVisibilityPasses;
      // Not on noisy views: read through a Gaussian of more than a sample, a sample's colour
      // already holds the other side's, and the one-sided window only averages less noise.
      visibility.same_side_window = views.noise_level() <= kNoisyViewLevels;
      visibility.edge_samples = kNarrowVisibilityEdge;
      visibility.far_side_plane = true;
    }
    // On noisy views the best of the near side's several depths is partly the luckiest of
    // several noisy costs, and keeps the near side where the wall's is right (`hci-antinous`
    // with noise added, measured 1.6 and 3.1 levels: MSE x 100 +0.05 and +0.09-0.13 with it).
    if (views.noise_level() > kNoisyViewLevels) visibility.near_search_steps = 0;
    RefineSilhouettesByVisibility(views, q, per_plane, choice.label, visibility);
  }
  DepthMap map;
  map.row = row;
  map.col = col;
  map.range = range;
  map.noise_levels = views.noise_level();
  map.near_nyquist_share = views.near_nyquist_share();
  map.read_sigma = views.read_sigma();
  map.camera_blur_sigma = views.camera_blur_sigma();
  map.views_too_dark = views.too_dark();
  map.reach = volume_options.reach;
  map.confidence = choice.confidence.clone();
  LessConfidentNearDepthEdges(choice.label, kEdgeJumpPixels / per_plane, map.confidence);
  map.depth.create(choice.label.size(), CV_32FC1);
  for (int y = 0; y < choice.label.rows; ++y)
    for (int x = 0; x < choice.label.cols; ++x) {
      const double qq =
          q.front() + (q.back() - q.front()) * choice.label.at<float>(y, x) / (labels - 1);
      map.depth.at<float>(y, x) = float(1.0 / qq);
    }
  return map;
}

void EstimateDepthSet(const LightField& lf, DepthSet& set,
                      const std::function<bool(int, int)>& needed, const PlaneSweepOptions& options,
                      const std::function<void(int, int)>& progress) {
  const auto& d = lf.dims();
  std::vector<std::pair<int, int>> todo;
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c)
      if (!set.has(r, c) && needed(r, c)) todo.emplace_back(r, c);
  if (todo.empty()) return;
  PlaneSweepOptions o = options;
  // The range from the central view with the options as given (a single view's reach), then
  // every view with the set's.
  if (!o.range) {
    o.range = set.count() > 0 ? set.range()
                              : EstimateDepthRange(lf, (d.rows - 1) / 2, (d.cols - 1) / 2, o);
  }
  // Each view's neighbours alone (8 views), unless they see the scene so narrowly apart that
  // disparities of a fraction of a sample need the views two steps away to resolve (docs/depth.md,
  // "The set's reach at narrow baselines").
  if (o.reach <= 0)
    o.reach = SeesTheSceneNarrowly(lf, (d.rows - 1) / 2, (d.cols - 1) / 2, *o.range)
                  ? kNarrowSetReach
                  : 1;
  std::mutex mutex;
  std::atomic<int> done{0};
  tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t i) {
    DepthMap map = EstimateDepth(lf, todo[i].first, todo[i].second, o);
    std::lock_guard lock(mutex);
    set.set(std::move(map));
    if (progress) progress(++done, int(todo.size()));
  });
}

}  // namespace lfcam
