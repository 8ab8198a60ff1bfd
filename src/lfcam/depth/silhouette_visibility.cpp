#include "lfcam/depth/silhouette_visibility.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "lfcam/depth/bilinear_read.h"

namespace lfcam {
namespace {

// The depths a sample is judged at: the far one, its own, and its own moved by up to
// kMaxNearSteps steps each way.
constexpr int kMaxNearSteps = 3;
constexpr int kHypotheses = 2 + 2 * kMaxNearSteps;
using HypothesisSums = std::array<CostSum, kHypotheses>;
using HypothesisViews = std::array<int, kHypotheses>;

// A sample on the near side of a depth edge, and the two depths it is judged between.
struct EdgeSample {
  int x = 0, y = 0;
  float near = 0, far = 0;  // labels (near: the smaller)
  HypothesisSums sum{};     // the views' costs: [0] far, [1] near, then near moved
  HypothesisViews seen{};   // the views that see the point there
};

// The samples of a candidate's 3 x 3 window that one side's depths are judged by, row by row:
// their labels, NaN where left out.
struct WindowSide {
  std::array<float, 9> label;
};

// std::lround's rounding (half away from zero) inline: the library call was 4% of `lfcam depth
// --all` (docs/benchmarks.md). v less its truncation is exact; no branch on the fraction (a row's
// splatted samples round whichever way, unpredictably); clamped to int's range less one (any such
// is off the map).
int RoundHalfAway(double v) {
  constexpr double kLimit = std::numeric_limits<int>::max() - 1;
  v = std::clamp(v, -kLimit, kLimit);
  const int t = static_cast<int>(v);
  const double fraction = v - static_cast<double>(t);
  return t + int(fraction >= 0.5) - int(fraction <= -0.5);
}

// What the views' costs are read with: the map, the colours, where each depth lies in a view.
struct CostReads {
  const std::vector<SweepViews::ReadShift>& shifts;
  const cv::Mat& label;
  const std::array<cv::Mat, 3>& reference;
  const std::vector<std::array<cv::Mat, 3>>& view_colour;
  bool blurred;  // the colours float copies through the sweep's Gaussian, or its 16-bit planes
  float packed_scale;
  double q0, dq;          // the planes' inverse depths: q0 + dq * label
  float edge, tolerance;  // in labels
  const SilhouetteVisibilityOptions& o;
  const std::vector<float>& near_offsets;  // hypothesis j >= 1: the near label moved by [j - 1]
};

// Adds to each candidate's sums the views' costs at its hypotheses first .. last - 1 (0: the far
// depth, 1 ..: the near one, moved), over the views that see the point there.
void SumViewCosts(const CostReads& r, std::vector<EdgeSample>& candidates, int first, int last) {
  const int w = r.label.cols, h = r.label.rows;
  const cv::Mat& label = r.label;
  const SilhouetteVisibilityOptions& o = r.o;
  const double q0 = r.q0, dq = r.dq;
  const float edge = r.edge, tolerance = r.tolerance;
  // The samples whose splat can hide a candidate's read: a sample lands, in any view, as far
  // from its own place as its label puts it, a candidate's read as far as its depths put it,
  // so within the views' largest change of shift over the map's labels (and a sample for the
  // rounding, one for the holes' filling below) of a candidate. Later passes have few.
  double label_lo = 0, label_hi = 0;
  cv::minMaxLoc(label, &label_lo, &label_hi);
  double reach_x = 0, reach_y = 0;
  for (const SweepViews::ReadShift& s : r.shifts) {
    reach_x = std::max(reach_x, std::abs(dq * s.per_q.x) * (label_hi - label_lo));
    reach_y = std::max(reach_y, std::abs(dq * s.per_q.y) * (label_hi - label_lo));
  }
  const int splat_x = int(std::ceil(reach_x)) + 2, splat_y = int(std::ceil(reach_y)) + 2;
  cv::Mat splatted(h, w, CV_8U, cv::Scalar(0));
  for (const EdgeSample& c : candidates) splatted.at<unsigned char>(c.y, c.x) = 1;
  cv::dilate(splatted, splatted,
             cv::getStructuringElement(cv::MORPH_RECT, {2 * splat_x + 1, 2 * splat_y + 1}));
  std::vector<char> row_splatted(std::size_t(h), 0);
  for (int y = 0; y < h; ++y) row_splatted[std::size_t(y)] = cv::countNonZero(splatted.row(y)) > 0;
  // Each candidate's window for each side (the far depth's, the near one's): the labels of the
  // samples it reads, NaN for those it leaves out (off the map, or on the edge's other side).
  const bool own_depths = o.same_side_window && o.side_at_own_depths;
  std::vector<std::array<WindowSide, 2>> windows(candidates.size());
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const EdgeSample& c = candidates[k];
    for (int side = 0; side < 2; ++side) {
      const float side_label = side == 0 ? c.far : c.near;
      for (int n = 0; n < 9; ++n) {
        const int rx = c.x + n % 3 - 1, ry = c.y + n / 3 - 1;
        float& own = windows[k][std::size_t(side)].label[std::size_t(n)];
        own = std::numeric_limits<float>::quiet_NaN();
        if (rx < 0 || ry < 0 || rx >= w || ry >= h) continue;
        const float l = label.at<float>(ry, rx);
        // The window's samples on the edge's other side are not this hypothesis's. Read at their
        // own depths, a sample is on the far side where it is farther than the near label by
        // more than the threshold, on the near side where it is nearer than the far depth by as
        // much (a slanted side's samples all count); read at the judged depth, only those within
        // the threshold of that side's label.
        if (o.same_side_window && n != 4) {
          const bool same_side = !own_depths ? std::abs(l - side_label) <= edge
                                 : side == 0 ? l > c.near + edge
                                             : l < c.far - edge;
          if (!same_side) continue;
        }
        own = l;
      }
    }
  }
  // Each view on its own (in parallel): its z-buffer, then the candidates' costs read in it.
  struct Sums {
    std::vector<HypothesisSums> sum;
    std::vector<HypothesisViews> seen;
    cv::Mat hidden_by;            // the nearest label splatted there
    std::vector<int> to_x, to_y;  // where a row's samples land
  };
  tbb::enumerable_thread_specific<Sums> per_thread([&] {
    return Sums{std::vector<HypothesisSums>(candidates.size()),
                std::vector<HypothesisViews>(candidates.size()), cv::Mat(h, w, CV_32F),
                std::vector<int>(std::size_t(w)), std::vector<int>(std::size_t(w))};
  });
  tbb::parallel_for(0, int(r.shifts.size()), [&](int i) {
    Sums& sums = per_thread.local();
    cv::Mat& hidden_by = sums.hidden_by;
    const SweepViews::ReadShift& s = r.shifts[std::size_t(i)];
    hidden_by.setTo(std::numeric_limits<float>::infinity());
    int* to_x = sums.to_x.data();
    int* to_y = sums.to_y.data();
    for (int y = 0; y < h; ++y) {
      if (!row_splatted[std::size_t(y)]) continue;
      const float* row = label.ptr<float>(y);
      const unsigned char* needed = splatted.ptr<unsigned char>(y);
      // Run by run of the samples needed (the candidates' neighbourhoods): where each lands,
      // with no branch on the rounding, then the nearest kept.
      for (int x0 = 0; x0 < w;) {
        while (x0 < w && !needed[x0]) ++x0;
        int x1 = x0;
        while (x1 < w && needed[x1]) ++x1;
        for (int x = x0; x < x1; ++x) {
          const cv::Point2d at = s.At(x, y, q0 + dq * row[x]);
          to_x[x] = RoundHalfAway(at.x);
          to_y[x] = RoundHalfAway(at.y);
        }
        for (int x = x0; x < x1; ++x) {
          const int tx = to_x[x], ty = to_y[x];
          if (unsigned(tx) >= unsigned(w) || unsigned(ty) >= unsigned(h)) continue;
          float& z = hidden_by.ptr<float>(ty)[tx];
          z = std::min(z, row[x]);
        }
        x0 = x1;
      }
    }
    // A point splatted between samples leaves holes: each takes its neighbours' nearest.
    cv::erode(hidden_by, hidden_by, cv::Mat::ones(2, 2, CV_8U));
    const std::array<cv::Mat, 3>& v = r.view_colour[std::size_t(i)];
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      const EdgeSample& c = candidates[k];
      for (int j = first; j < last; ++j) {
        // The window's samples of this hypothesis's side: those of the far label for the far
        // depth, of the sample's own for its own however moved.
        const float side = j == 0 ? c.far : c.near;
        const float hypothesis = j == 0 ? c.far : c.near + r.near_offsets[std::size_t(j - 1)];
        const double qq = q0 + dq * hypothesis;
        const cv::Point2d at = s.At(c.x, c.y, qq);
        const double px = at.x, py = at.y;
        const int tx = RoundHalfAway(px), ty = RoundHalfAway(py);
        if (tx < 0 || ty < 0 || tx >= w || ty >= h) continue;
        if (hidden_by.at<float>(ty, tx) < hypothesis - tolerance) continue;
        double cost = 0;
        int counted = 0;
        const WindowSide& window = windows[k][j == 0 ? 0 : 1];
        for (int n = 0; n < 9; ++n) {
          const float own = window.label[std::size_t(n)];
          if (std::isnan(own)) continue;
          const int dx = n % 3 - 1, dy = n / 3 - 1;
          const int rx = c.x + dx, ry = c.y + dy;
          // Where the read is: the sample's, moved by the window's offset, or the neighbour's
          // own depth moved as the hypothesis moves the side's.
          cv::Point2d read_at{px + dx, py + dy};
          if (own_depths && n != 4) read_at = s.At(rx, ry, q0 + dq * (own + (hypothesis - side)));
          float read[3];
          const bool inside =
              r.blurred ? BilinearAt3<float>(v, read_at.x, read_at.y, 1.0f, read)
                        : BilinearAt3<std::int16_t>(v, read_at.x, read_at.y, r.packed_scale, read);
          if (!inside) continue;
          float d = 0;
          for (std::size_t ch = 0; ch < 3; ++ch)
            d += std::abs(read[ch] - r.reference[ch].at<float>(ry, rx));
          cost += std::min(d / 3.0, o.color_cap);
          ++counted;
        }
        if (counted == 0) continue;
        sums.sum[k][std::size_t(j)].Add(cost / counted);
        ++sums.seen[k][std::size_t(j)];
      }
    }
  });
  for (const Sums& sums : per_thread)
    for (std::size_t k = 0; k < candidates.size(); ++k)
      for (int j = first; j < last; ++j) {
        candidates[k].sum[std::size_t(j)] += sums.sum[k][std::size_t(j)];
        candidates[k].seen[std::size_t(j)] += sums.seen[k][std::size_t(j)];
      }
}

}  // namespace

float FarSidePlaneAt(const cv::Mat& label, int x, int y, float beyond, float farthest, float edge) {
  // A plane through the window's far-side samples, label = a + b dx + c dy, by least squares
  // (the normal equations), its slopes held towards none by a prior of kSlopePrior: samples in
  // one column or row, as along a straight edge, give no slope across it.
  constexpr double kSlopePrior = 0.5;
  cv::Matx33d normal = cv::Matx33d::zeros();
  cv::Vec3d moment(0, 0, 0);
  int samples = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int rx = x + dx, ry = y + dy;
      if ((dx == 0 && dy == 0) || rx < 0 || ry < 0 || rx >= label.cols || ry >= label.rows)
        continue;
      const float l = label.at<float>(ry, rx);
      if (!(l > beyond)) continue;
      const cv::Vec3d v(1.0, dx, dy);
      normal += v * v.t();
      moment += v * double(l);
      ++samples;
    }
  if (samples < 3) return farthest;
  normal(1, 1) += kSlopePrior;
  normal(2, 2) += kSlopePrior;
  cv::Vec3d plane;
  if (std::abs(cv::determinant(normal)) <= 1e-6 || !cv::solve(normal, moment, plane))
    return farthest;
  if (!(plane[0] > beyond)) return farthest;
  return float(std::min(plane[0], double(farthest) + edge));
}

cv::Mat ReachedByTheFarSide(const cv::Mat& label, const cv::Mat& far, float edge) {
  const int w = label.cols, h = label.rows;
  cv::Mat reached(h, w, CV_8U, cv::Scalar(0));
  const auto wants = [&](int x, int y) {
    return !std::isnan(far.at<float>(y, x)) && !reached.at<unsigned char>(y, x);
  };
  constexpr std::array<std::array<int, 2>, 4> kSides{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
  std::vector<cv::Point> queue;
  // Next to a sample the map already puts at least as far (less the edge's threshold): one
  // that does not itself move.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!wants(x, y)) continue;
      const float to = far.at<float>(y, x);
      for (const auto& [dx, dy] : kSides) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= w || ny >= h || !std::isnan(far.at<float>(ny, nx))) continue;
        if (label.at<float>(ny, nx) >= to - edge) {
          reached.at<unsigned char>(y, x) = 1;
          queue.emplace_back(x, y);
          break;
        }
      }
    }
  // Then next to one that moves to a depth at least as far (less the threshold).
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const cv::Point at = queue[i];
    const float to = far.at<float>(at);
    for (const auto& [dx, dy] : kSides) {
      const int nx = at.x + dx, ny = at.y + dy;
      if (nx < 0 || ny < 0 || nx >= w || ny >= h || !wants(nx, ny)) continue;
      if (to >= far.at<float>(ny, nx) - edge) {
        reached.at<unsigned char>(ny, nx) = 1;
        queue.emplace_back(nx, ny);
      }
    }
  }
  return reached;
}

int RefineSilhouettesByVisibility(const SweepViews& views, const std::vector<double>& q,
                                  double samples_per_label, cv::Mat& label,
                                  const SilhouetteVisibilityOptions& o) {
  const auto shifts = views.ReadShifts();
  const int n = int(q.size());
  if (!shifts || n < 2 || !(samples_per_label > 0) || views.view_count() == 0) return 0;
  const int w = label.cols, h = label.rows;
  const double q0 = q.front(), dq = (q.back() - q.front()) / (n - 1);
  const float edge = float(o.edge_samples / samples_per_label);
  const float tolerance = float(o.tolerance_samples / samples_per_label);
  const int fewest_views = std::max(2, views.view_count() / 10);
  // The near side's depths: its own and those moved by steps of near_search_samples (the
  // nearest view's shift) each way, in labels.
  std::vector<float> near_offsets{0.0f};
  const int steps = std::clamp(o.near_search_steps, 0, kMaxNearSteps);
  for (int k = 1; k <= steps; ++k) {
    const float offset = float(k * o.near_search_samples / samples_per_label);
    near_offsets.push_back(offset);
    near_offsets.push_back(-offset);
  }
  const int hypotheses = 1 + int(near_offsets.size());
  // The colour planes, read through the sweep's Gaussian where its views are.
  const auto colour = [&](int i) {
    std::array<cv::Mat, 3> rgb = views.Colour(i);
    if (views.read_sigma() > 0)
      for (cv::Mat& m : rgb) cv::GaussianBlur(m, m, {0, 0}, views.read_sigma());
    return rgb;
  };
  const std::array<cv::Mat, 3> reference = colour(-1);
  // The other views' as read: the sweep's own 16-bit planes, not copied, where it reads them
  // as they are (a float copy of 100 views of 1248 x 1152 would be 1.7 GB); float copies
  // through its Gaussian where it does not.
  const bool blurred = views.read_sigma() > 0;
  std::vector<std::array<cv::Mat, 3>> view_colour;
  for (int i = 0; i < views.view_count(); ++i)
    view_colour.push_back(blurred ? colour(i) : views.PackedColour(i));
  const float packed_scale = float(1.0 / SweepViews::kPackedColour);
  const cv::Mat kernel = cv::Mat::ones(o.window, o.window, CV_8U);
  int changed = 0;
  cv::Mat moved_here, near_moved;
  for (int pass = 0; pass < o.passes; ++pass) {
    cv::Mat nearest, farthest, jump(h, w, CV_32F, cv::Scalar(0));
    cv::erode(label, nearest, kernel);
    cv::dilate(label, farthest, kernel);
    // A depth edge is a jump between neighbouring samples, not a slope: a surface seen at a
    // grazing angle spans many planes within the window without one.
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float l = label.at<float>(y, x);
        float& j = jump.at<float>(y, x);
        if (x + 1 < w) j = std::max(j, std::abs(label.at<float>(y, x + 1) - l));
        if (y + 1 < h) j = std::max(j, std::abs(label.at<float>(y + 1, x) - l));
      }
    cv::dilate(jump, jump, kernel);
    std::vector<EdgeSample> candidates;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float l = label.at<float>(y, x), a = nearest.at<float>(y, x),
                    b = farthest.at<float>(y, x);
        // After the first pass, only where the last one moved a sample next to it.
        if (jump.at<float>(y, x) > edge && l - a < b - l &&
            (pass == 0 || near_moved.at<unsigned char>(y, x)))
          candidates.push_back(
              {x, y, l, o.far_side_plane ? FarSidePlaneAt(label, x, y, l + edge, b, edge) : b});
      }
    if (candidates.empty()) break;
    const CostReads reads{*shifts, label, reference, view_colour, blurred, packed_scale,
                          q0,      dq,    edge,      tolerance,   o,       near_offsets};
    SumViewCosts(reads, candidates, 0, 2);
    // Where the far depth matches better than the near one's own, the near one moved as well:
    // elsewhere the far depth cannot win.
    std::vector<EdgeSample> closer;
    std::vector<std::size_t> closer_at;
    for (std::size_t k = 0; k < candidates.size() && hypotheses > 2; ++k) {
      const EdgeSample& c = candidates[k];
      if (c.seen[0] >= fewest_views && c.seen[1] >= fewest_views &&
          c.sum[0].value() / c.seen[0] < c.sum[1].value() / c.seen[1]) {
        closer.push_back(c);
        closer_at.push_back(k);
      }
    }
    if (!closer.empty()) {
      SumViewCosts(reads, closer, 2, hypotheses);
      for (std::size_t i = 0; i < closer.size(); ++i) candidates[closer_at[i]] = closer[i];
    }
    // The samples whose far depth matches better; of those, the ones the far side reaches move.
    cv::Mat wanting(h, w, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
    // The near side at its best depth of those tried (still nearer than the far one by more
    // than the edge's threshold); the sample keeps its own label whichever wins.
    for (const EdgeSample& c : candidates) {
      if (c.seen[0] < fewest_views || c.seen[1] < fewest_views) continue;
      double near_cost = c.sum[1].value() / c.seen[1];
      for (int j = 2; j < hypotheses; ++j)
        if (c.seen[std::size_t(j)] >= fewest_views &&
            c.near + near_offsets[std::size_t(j - 1)] < c.far - edge)
          near_cost = std::min(near_cost, c.sum[std::size_t(j)].value() / c.seen[std::size_t(j)]);
      if (c.sum[0].value() / c.seen[0] < near_cost) wanting.at<float>(c.y, c.x) = c.far;
    }
    moved_here = ReachedByTheFarSide(label, wanting, edge);
    const int moved = cv::countNonZero(moved_here);
    wanting.copyTo(label, moved_here);
    changed += moved;
    cv::dilate(moved_here, near_moved, kernel);
    if (moved == 0) break;
  }
  return changed;
}

}  // namespace lfcam
