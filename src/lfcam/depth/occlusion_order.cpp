#include "lfcam/depth/occlusion_order.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/depth/bilinear_read.h"
#include "lfcam/depth/cost_volume.h"
#include "lfcam/depth/plane_sweep.h"

namespace lfcam {
namespace {

// A pair of neighbouring samples votes where one view at least moves them this many samples
// relative to each other (and only such views count), and where its two sides' mismatch differs
// by this much (sRGB, 0 .. 1, the mean over R, G and B). Measured on the sets of docs/format.md,
// one sample apart let a third more pairs vote, more of them wrongly (the `paper` gantry's
// 79% as named, against 91%).
constexpr double kFewestSamplesApart = 2.0;
constexpr double kSmallestMismatch = 0.01;
// A depth edge's sides each go on for kSideSamples samples, each step at most this share of the
// jump between them: a slope steps alike on every sample, and a repeating texture's false depth
// makes islands of a few samples, whose edges voted the wrong way as often as the right one.
constexpr double kSlopeShare = 0.25;
constexpr int kSideSamples = 4;

// A side's mismatch, summed over the closing and over the opening views.
struct SideCost {
  double closing = 0, opening = 0;
  int closing_n = 0, opening_n = 0;
  bool complete() const { return closing_n > 0 && opening_n > 0; }
  double excess() const { return closing / closing_n - opening / opening_n; }
};

// Views twice this many samples a side or more are reduced a whole number of times to between
// this and twice it (those smaller are measured as they are): the check
// asks for a depth edge's side, not its place, and a view four times as large only makes its
// textureless spans four times as long for the global step to fill.
constexpr int kLargestSide = 512;
// Both sides of an edge must be this confident three samples out (the map's confidence is a
// quarter of its own within two samples of an edge): a textureless span's fill says nothing.
constexpr float kLeastConfidence = 0.02f;

// `lf` reduced `factor` times each way (8-bit sRGB views, each an area average), its st domain
// and cameras' centres kept; `lf` itself where it is not 8-bit or needs no reduction.
LightField Reduced(const LightField& lf, int factor) {
  const LightFieldDims& d = lf.dims();
  if (factor <= 1 || lf.sample_type() != SampleType::kSrgb8 || lf.has_view_windows()) return lf;
  LightFieldDims small = d;
  small.n_s = std::max(2, d.n_s / factor);
  small.n_t = std::max(2, d.n_t / factor);
  LightField out(small, lf.sample_type(), lf.slab());
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) {
      const cv::Mat view(d.n_t, d.n_s, CV_8UC3, const_cast<std::uint8_t*>(lf.view_data(r, c)));
      cv::Mat into(small.n_t, small.n_s, CV_8UC3, out.mutable_view_data(r, c));
      cv::resize(view, into, into.size(), 0, 0, cv::INTER_AREA);
    }
  std::vector<ViewPose> poses = lf.measured_poses();
  for (ViewPose& p : poses) p.intrinsics.reset();  // the full views' cameras
  if (!poses.empty()) out.set_measured_poses(std::move(poses));
  return out;
}

}  // namespace

OcclusionOrder MeasureOcclusionOrder(const LightField& full) {
  const auto start = std::chrono::steady_clock::now();
  OcclusionOrder out;
  const auto done = [&] {
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  };
  const int largest = std::max(full.dims().n_s, full.dims().n_t);
  const LightField lf = Reduced(full, largest / kLargestSide);
  const LightFieldDims& d = lf.dims();
  if (d.view_count() < 2) {
    out.why = "a single view";
    return done();
  }
  const int row = d.rows / 2, col = d.cols / 2;
  // The map without the one step that assumes which side of an edge is near.
  PlaneSweepOptions sweep;
  sweep.silhouette_visibility = false;
  sweep.slant_prior = false;
  sweep.reach = 2;
  std::optional<DepthMap> map;
  std::optional<SweepViews> views_or;
  try {
    map = EstimateDepth(lf, row, col, sweep);
    // The views within reach 4, each view's brightness made the reference's: a plenoptic
    // camera's outer views, vignetted, are darker, and the brighter side of an edge would
    // mismatch more in them whichever side is near.
    CostVolumeOptions within_reach_4;
    within_reach_4.equalise_brightness = true;
    views_or.emplace(lf, row, col, within_reach_4);
  } catch (const Error& e) {
    out.why = e.what();
    return done();
  }
  const SweepViews& views = *views_or;
  const auto shifts = views.ReadShifts();
  if (!shifts) {
    out.why = "the views are warped by a homography (the st-plane not parallel to the array)";
    return done();
  }
  const int w = views.width(), h = views.height();
  cv::Mat inverse_depth;
  cv::resize(map->depth, inverse_depth, {w, h}, 0, 0, cv::INTER_NEAREST);
  cv::divide(1.0, inverse_depth, inverse_depth);
  cv::Mat confidence;
  if (!map->confidence.empty())
    cv::resize(map->confidence, confidence, {w, h}, 0, 0, cv::INTER_NEAREST);
  const auto confident = [&](cv::Point p) {
    if (p.x < 0 || p.y < 0 || p.x >= w || p.y >= h) return false;
    return confidence.empty() || confidence.at<float>(p) >= kLeastConfidence;
  };
  double largest_per_q = 0;
  for (const SweepViews::ReadShift& s : *shifts)
    largest_per_q = std::max({largest_per_q, std::abs(s.per_q.x), std::abs(s.per_q.y)});

  // The pairs of neighbouring samples some view moves kFewestSamplesApart or more apart.
  struct Edge {
    cv::Point a, dir;
    float qa = 0, qb = 0;
    std::array<SideCost, 2> side;  // 0: a and the sample before it; 1: b and the one after it
  };
  std::vector<Edge> edges;
  for (const cv::Point dir : {cv::Point(1, 0), cv::Point(0, 1)})
    for (int y = 0; y + dir.y < h; ++y)
      for (int x = 0; x + dir.x < w; ++x) {
        const cv::Point a(x, y), b = a + dir;
        const float qa = inverse_depth.at<float>(a), qb = inverse_depth.at<float>(b);
        if (!std::isfinite(qa) || !std::isfinite(qb) ||
            std::abs(qa - qb) * largest_per_q < kFewestSamplesApart)
          continue;
        // A jump, not a slope: each side goes on for kSideSamples with steps that are each a
        // small part of the jump (and not an island of a few samples at a repeating texture's
        // false depth).
        const float jump = std::abs(qa - qb);
        bool sides = true;
        for (int k = 1; k <= kSideSamples && sides; ++k) {
          const cv::Point before = a - k * dir, after = b + k * dir;
          if (before.x < 0 || before.y < 0 || after.x >= w || after.y >= h) {
            sides = false;
            break;
          }
          sides = std::abs(inverse_depth.at<float>(before) -
                           inverse_depth.at<float>(before + dir)) <= kSlopeShare * jump &&
                  std::abs(inverse_depth.at<float>(after) - inverse_depth.at<float>(after - dir)) <=
                      kSlopeShare * jump;
        }
        if (!sides) continue;
        if (!confident(a - 3 * dir) || !confident(b + 3 * dir)) continue;
        edges.push_back({a, dir, qa, qb, {}});
      }

  const std::array<cv::Mat, 3> reference = views.Colour(-1);
  for (int i = 0; i < views.view_count(); ++i) {
    const std::array<cv::Mat, 3> colour = views.Colour(i);
    const SweepViews::ReadShift& s = (*shifts)[std::size_t(i)];
    // Sample p's mismatch in this view at its own depth; false where unknown or outside it.
    const auto mismatch = [&](cv::Point p, double* cost) {
      if (p.x < 0 || p.y < 0 || p.x >= w || p.y >= h) return false;
      const float q = inverse_depth.at<float>(p);
      if (!std::isfinite(q)) return false;
      const cv::Point2d at = s.At(p.x, p.y, q);
      const double vx = at.x, vy = at.y;
      float v[3];
      if (!BilinearAt3<float>(colour, vx, vy, 1.0f, v)) return false;
      double sum = 0;
      for (std::size_t c = 0; c < 3; ++c) sum += std::abs(double(v[c]) - reference[c].at<float>(p));
      *cost = sum / 3;
      return true;
    };
    for (Edge& e : edges) {
      // How far apart the two surfaces' reads lie in this view (a scaled view's scale too).
      const double qd = double(e.qa - e.qb);
      const cv::Point2d r(s.per_q.x * qd + e.a.x * s.scale_per_q.x * qd,
                          s.per_q.y * qd + e.a.y * s.scale_per_q.y * qd);
      const double apart = r.x * e.dir.x + r.y * e.dir.y;  // > 0: a's surface moves toward b's
      if (std::abs(apart) < kFewestSamplesApart) continue;
      const bool closing = apart > 0;
      for (int side = 0; side < 2; ++side)
        for (int step = 0; step < 2; ++step) {
          const cv::Point p = side == 0 ? e.a - step * e.dir : e.a + (1 + step) * e.dir;
          double cost = 0;
          if (!mismatch(p, &cost)) continue;
          SideCost& c = e.side[std::size_t(side)];
          if (closing)
            c.closing += cost, ++c.closing_n;
          else
            c.opening += cost, ++c.opening_n;
        }
    }
  }
  for (const Edge& e : edges) {
    if (!e.side[0].complete() || !e.side[1].complete()) continue;
    const std::size_t far = e.qa < e.qb ? 0 : 1;  // the smaller inverse depth
    const double stat = e.side[far].excess() - e.side[1 - far].excess();
    if (stat > kSmallestMismatch)
      ++out.as_named;
    else if (stat < -kSmallestMismatch)
      ++out.reversed;
  }

  const int votes = out.as_named + out.reversed;
  if (votes < kFewestOcclusionVotes) {
    out.why = fmt::format("{} depth edges voted, fewer than {}", votes, kFewestOcclusionVotes);
  } else if (out.as_named >= kOcclusionMajority * votes) {
    out.verdict = OcclusionVerdict::kAsNamed;
  } else if (out.reversed >= kOcclusionMajority * votes) {
    out.verdict = OcclusionVerdict::kReversed;
  } else {
    out.why = fmt::format("the votes split {} to {}", out.as_named, out.reversed);
  }
  return done();
}

LightField WithViewsTurnedHalfATurn(const LightField& lf) {
  if (lf.has_view_windows())
    throw Error("a light field whose views have their own st windows cannot be turned");
  LightField turned(lf.dims(), lf.sample_type(), lf.slab());
  const LightFieldDims& d = lf.dims();
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c)
      std::memcpy(turned.mutable_view_data(r, c), lf.view_data(d.rows - 1 - r, d.cols - 1 - c),
                  lf.view_bytes());
  if (!lf.measured_poses().empty()) turned.set_measured_poses(lf.measured_poses());
  turned.metadata() = lf.metadata();
  return turned;
}

std::string ToString(OcclusionVerdict verdict) {
  switch (verdict) {
    case OcclusionVerdict::kAsNamed:
      return "as-named";
    case OcclusionVerdict::kReversed:
      return "reversed";
    case OcclusionVerdict::kUndecided:
      break;
  }
  return "undecided";
}

std::string Describe(const OcclusionOrder& o) {
  const int votes = o.as_named + o.reversed;
  const std::string counts = fmt::format(
      "of {} depth edges in the central view, {} hide their far side from the views that "
      "close over it and {} their near side",
      votes, o.as_named, o.reversed);
  switch (o.verdict) {
    case OcclusionVerdict::kAsNamed:
      return fmt::format("near and far as named ({})", counts);
    case OcclusionVerdict::kReversed:
      return fmt::format("near and far exchanged as named ({})", counts);
    case OcclusionVerdict::kUndecided:
      break;
  }
  return fmt::format("near and far not told by the occlusions ({}), taken as named", o.why);
}

}  // namespace lfcam
