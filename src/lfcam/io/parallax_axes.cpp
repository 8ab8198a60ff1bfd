#include "lfcam/io/parallax_axes.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"

namespace lfcam {
namespace fs = std::filesystem;

namespace {

// Views are tracked at most this many pixels a side (a larger view is shrunk first).
constexpr int kTrackSide = 1024;
constexpr int kFewestPoints = 40;
// Tracking back must land this close to where a point started (px at the tracking scale).
constexpr float kRoundTripPx = 0.5f;
// |correlation| above which the axes are judged (agree, or one reversed).
constexpr double kDecisive = 0.5;
// A parallel rig's points' parallax counted for its sign from this many px, and taken as one
// sign where this share of them agree.
constexpr double kSignPx = 0.25;
constexpr double kOneSign = 0.8;

// The spread of `v`: its 10th to 90th percentile.
double Spread(std::vector<double> v) {
  if (v.size() < 10) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() * 9 / 10] - v[v.size() / 10];
}

// Pearson's correlation of x and y, each first clipped to its 2nd .. 98th percentile: a
// mistracked point is a gross outlier, one of which moves Pearson's r. (Not a rank correlation,
// nor a median's deviation: a scene of a few depths tracks as a few clusters of points, whose
// ranks and medians within the largest say nothing.)
double ClippedCorrelation(std::vector<double> x, std::vector<double> y) {
  const auto clip = [](std::vector<double>& v) {
    std::vector<double> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    const double lo = sorted[sorted.size() * 2 / 100], hi = sorted[sorted.size() * 98 / 100];
    for (double& a : v) a = std::clamp(a, lo, hi);
  };
  if (x.size() < 3) return 0;
  clip(x), clip(y);
  const double n = double(x.size());
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i], sy += y[i];
    sxx += x[i] * x[i], syy += y[i] * y[i], sxy += x[i] * y[i];
  }
  const double vx = sxx - sx * sx / n, vy = syy - sy * sy / n, cxy = sxy - sx * sy / n;
  return vx > 0 && vy > 0 ? cxy / std::sqrt(vx * vy) : 0;
}

// Parallel cameras (centred sensors): every point moves against its camera by f / Z > 0, so
// each axis is judged on its own by the sign its points' parallax takes (those that move by
// kSignPx or more: the rest may lie at infinity). Nullopt where either axis's points do not take
// one sign (fewer than 80% of them), so that the two axes' correlation decides.
std::optional<AxesVerdict> ParallaxSigns(const std::vector<double>& row_x,
                                         const std::vector<double>& col_y, double dx, double dy) {
  const auto share_against = [](const std::vector<double>& motion, double baseline) {
    int against = 0, counted = 0;
    for (double m : motion)
      if (std::abs(m) >= kSignPx) ++counted, against += (m * baseline < 0);
    return counted >= kFewestPoints ? std::optional(double(against) / counted) : std::nullopt;
  };
  // Along the row, a point moves against the camera (x); along the column, with it (y down).
  const auto row = share_against(row_x, dx);
  const auto col = share_against(col_y, -dy);
  const auto reversed = [](double share) -> std::optional<bool> {
    if (share >= kOneSign) return false;
    if (share <= 1 - kOneSign) return true;
    return std::nullopt;
  };
  if (!row || !col) return std::nullopt;
  const auto cols_reversed = reversed(*row), rows_reversed = reversed(*col);
  if (!cols_reversed || !rows_reversed) return std::nullopt;
  if (*cols_reversed && *rows_reversed) return AxesVerdict::kBothReversed;
  if (*cols_reversed) return AxesVerdict::kColsReversed;
  return *rows_reversed ? AxesVerdict::kRowsReversed : AxesVerdict::kAgree;
}

// The centre view's corners (up to 3 000, pyramidal Lucas-Kanade) tracked into views, as
// read at `scale` (a view larger than kTrackSide a side is shrunk first).
class CornerTracks {
 public:
  // Empty (corners() == 0) where fewer than kFewestPoints corners are found.
  CornerTracks(const fs::path& dir, const GridView& centre) : dir_(dir) {
    const cv::Mat first = ReadImageGray8(dir / centre.file);
    scale_ = std::min(1.0, double(kTrackSide) / std::max(first.cols, first.rows));
    reference_ = Shrunk(first);
    cv::goodFeaturesToTrack(reference_, corners_, 3000, 0.005, 4.0, cv::noArray(), 5);
    if (int(corners_.size()) < kFewestPoints) corners_.clear();
  }
  std::size_t corners() const { return corners_.size(); }
  double scale() const { return scale_; }

  // Where each corner lands in `view`, NaN where tracking there and back disagrees.
  std::vector<cv::Point2f> Into(const GridView& view) const {
    const cv::Mat other = Shrunk(ReadImageGray8(dir_ / view.file));
    std::vector<cv::Point2f> there, back;
    std::vector<unsigned char> ok_there, ok_back;
    std::vector<float> error;
    const cv::Size window(21, 21);
    cv::calcOpticalFlowPyrLK(reference_, other, corners_, there, ok_there, error, window, 3);
    cv::calcOpticalFlowPyrLK(other, reference_, there, back, ok_back, error, window, 3);
    for (std::size_t i = 0; i < corners_.size(); ++i)
      if (!ok_there[i] || !ok_back[i] || cv::norm(back[i] - corners_[i]) > kRoundTripPx)
        there[i] = {NAN, NAN};
    return there;
  }

 private:
  cv::Mat Shrunk(cv::Mat grey) const {
    if (scale_ < 1.0) cv::resize(grey, grey, {}, scale_, scale_, cv::INTER_AREA);
    return grey;
  }
  fs::path dir_;
  double scale_ = 1;
  cv::Mat reference_;
  std::vector<cv::Point2f> corners_;
};

std::string TooFew() {
  return fmt::format("fewer than {} points of the centre view track", kFewestPoints);
}

// Why `views` cannot be compared (one of them missing, or a baseline between them zero); empty
// when they can.
std::string Unusable(std::initializer_list<const GridView*> views,
                     std::initializer_list<double> baselines) {
  for (const GridView* v : views)
    if (v->file.empty()) return "a view it compares is missing";
  for (double b : baselines)
    if (!(std::abs(b) > 0)) return "the views it compares stand at one place";
  return {};
}

// The 98th percentile of `px` (|parallax| over the views compared) a grid step of `steps`.
double LargestPerStep(const std::vector<double>& px, double steps) {
  std::vector<double> per_step;
  for (double p : px) per_step.push_back(std::abs(p) / steps);
  std::sort(per_step.begin(), per_step.end());
  return per_step[per_step.size() * 98 / 100];
}

// A single row (column) of views: the centre view against the views two steps either side.
// Nothing to check a rectified rig's one axis against, but its largest parallax is measured
// (where infinity is put, when nothing published says), a line whose views move across it is
// a line of the other kind, and parallel cameras' points move against the camera.
ParallaxAxes MeasureAlongOneLine(const fs::path& dir, const ImportedGrid& g) {
  ParallaxAxes out;
  out.single_line = true;
  const bool row = g.rows == 1;
  const char* line = row ? "row" : "column";
  const int rc = g.rows / 2, cc = g.cols / 2;
  const GridView& centre = g.view(rc, cc);
  const GridView& a = row ? g.view(0, std::max(0, cc - 2)) : g.view(std::max(0, rc - 2), 0);
  const GridView& b =
      row ? g.view(0, std::min(g.cols - 1, cc + 2)) : g.view(std::min(g.rows - 1, rc + 2), 0);
  out.views = fmt::format("{} against {} and {} (along its {})", centre.file, a.file, b.file, line);
  // The baseline from a to b: along the row x grows to the right, along the column y upward.
  const double baseline = row ? b.x_mm - a.x_mm : b.y_mm - a.y_mm;
  out.why = Unusable({&centre, &a, &b}, {baseline});
  if (!out.why.empty()) return out;
  const CornerTracks tracks(dir, centre);
  if (tracks.corners() == 0) {
    out.why = TooFew();
    return out;
  }
  const auto in_a = tracks.Into(a), in_b = tracks.Into(b);
  // Parallax along the line and across it, px of the views as they are, from a to b.
  std::vector<double> along, across;
  for (std::size_t i = 0; i < in_a.size(); ++i) {
    if (std::isnan(in_a[i].x) || std::isnan(in_b[i].x)) continue;
    const cv::Point2f m = (in_b[i] - in_a[i]) / float(tracks.scale());
    along.push_back(row ? m.x : m.y);
    across.push_back(row ? m.y : m.x);
  }
  out.points = int(along.size());
  if (out.points < kFewestPoints) {
    out.why = TooFew();
    return out;
  }
  if (g.pitch_mm > 0)
    out.largest_px_per_step = LargestPerStep(along, std::abs(baseline) / g.pitch_mm);
  out.spread_px = Spread(along);
  const double crossed = Spread(across);
  if (crossed >= kMinSpreadPx && crossed > 2 * out.spread_px) {
    out.verdict = AxesVerdict::kSwapped;
    return out;
  }
  if (out.spread_px < kMinSpreadPx) {
    out.why = fmt::format(
        "the scene's depth moves its points by {:.2f} px at most between the views compared "
        "({:.1f} needed)",
        out.spread_px, kMinSpreadPx);
    return out;
  }
  if (g.rig != RigModel::kParallel) {
    out.why = fmt::format(
        "a single {} of views (a rectified rig's parallax along one axis has no other to agree "
        "with; its largest, {:.2f} px a step, measured from {})",
        line, out.largest_px_per_step, out.views);
    return out;
  }
  // Along a row a point moves against the camera (x); along a column, with it (y down).
  int against = 0, counted = 0;
  for (double m : along)
    if (std::abs(m) >= kSignPx) ++counted, against += (m * (row ? baseline : -baseline) < 0);
  const double share = counted > 0 ? double(against) / counted : 0.5;
  if (counted >= kFewestPoints && share >= kOneSign)
    out.verdict = AxesVerdict::kAgree;
  else if (counted >= kFewestPoints && share <= 1 - kOneSign)
    out.verdict = row ? AxesVerdict::kColsReversed : AxesVerdict::kRowsReversed;
  else
    out.why = fmt::format("{:.0f}% of the points that move move against the camera ({} counted)",
                          100 * share, counted);
  return out;
}

}  // namespace

ParallaxAxes MeasureParallaxAxes(const fs::path& dir, const ImportedGrid& g) {
  ParallaxAxes out;
  const bool grid_is_parallel = g.rig == RigModel::kParallel;
  if (g.rows < 2 && g.cols < 2) {
    out.why = "a single view";
    return out;
  }
  if (g.rows < 2 || g.cols < 2) return MeasureAlongOneLine(dir, g);
  const int rc = g.rows / 2, cc = g.cols / 2;
  const GridView& centre = g.view(rc, cc);
  const GridView& left = g.view(rc, std::max(0, cc - 2));
  const GridView& right = g.view(rc, std::min(g.cols - 1, cc + 2));
  const GridView& down = g.view(std::max(0, rc - 2), cc);
  const GridView& up = g.view(std::min(g.rows - 1, rc + 2), cc);
  out.views = fmt::format("{} against {} and {} (along its row), {} and {} (along its column)",
                          centre.file, left.file, right.file, down.file, up.file);
  const double dx = right.x_mm - left.x_mm, dy = up.y_mm - down.y_mm;
  out.why = Unusable({&centre, &left, &right, &down, &up}, {dx, dy});
  if (!out.why.empty()) return out;
  const CornerTracks tracks(dir, centre);
  if (tracks.corners() == 0) {
    out.why = TooFew();
    return out;
  }
  const double scale = tracks.scale();
  const auto l = tracks.Into(left), r = tracks.Into(right), d = tracks.Into(down),
             u = tracks.Into(up);
  // Per unit of baseline, in px of the views as read: a camera moved right sees a point move
  // left by f / Z (plus its sensor's shift), one moved up sees it move down.
  std::vector<double> along_row, along_col, row_x, row_y, col_x, col_y;
  for (std::size_t i = 0; i < l.size(); ++i) {
    if (std::isnan(l[i].x) || std::isnan(r[i].x) || std::isnan(d[i].x) || std::isnan(u[i].x))
      continue;
    const cv::Point2f row = r[i] - l[i], col = u[i] - d[i];
    along_row.push_back(-row.x / dx);
    along_col.push_back(col.y / dy);
    row_x.push_back(row.x / scale), row_y.push_back(row.y / scale);
    col_x.push_back(col.x / scale), col_y.push_back(col.y / scale);
  }
  out.points = int(along_row.size());
  if (out.points < kFewestPoints) {
    out.why = TooFew();
    return out;
  }
  out.correlation = ClippedCorrelation(along_row, along_col);
  if (g.pitch_mm > 0) {
    const double row_steps = std::abs(dx) / g.pitch_mm, col_steps = std::abs(dy) / g.pitch_mm;
    std::vector<double> per_step;
    for (std::size_t i = 0; i < row_x.size(); ++i)
      per_step.push_back(std::max(std::abs(row_x[i]) / row_steps, std::abs(col_y[i]) / col_steps));
    out.largest_px_per_step = LargestPerStep(per_step, 1.0);
  }
  const double expected = std::min(Spread(row_x), Spread(col_y));
  const double crossed = std::max(Spread(row_y), Spread(col_x));
  out.spread_px = expected;
  if (crossed >= kMinSpreadPx && crossed > 2 * std::max(Spread(row_x), Spread(col_y)))
    out.verdict = AxesVerdict::kSwapped;
  else if (expected < kMinSpreadPx)
    out.why = fmt::format(
        "the scene's depth moves its points by {:.2f} px at most between the views compared "
        "({:.1f} needed)",
        expected, kMinSpreadPx);
  else if (const auto signs = grid_is_parallel ? ParallaxSigns(row_x, col_y, dx, dy) : std::nullopt)
    out.verdict = *signs;
  else if (out.correlation > kDecisive)
    out.verdict = AxesVerdict::kAgree;
  else if (out.correlation < -kDecisive)
    out.verdict = AxesVerdict::kRowsReversed;
  else
    out.why = fmt::format("the parallax along the row and along the column correlate by {:+.2f}",
                          out.correlation);
  return out;
}

namespace {

// `grid` laid out again as `rows` x `cols`: view (r, c) is grid's view at source(r, c), its
// position moved by `position`; the missing views' labels follow.
template <class Source, class Position>
ImportedGrid Rearranged(const ImportedGrid& grid, int rows, int cols, Source source,
                        Position position) {
  ImportedGrid g = grid;
  g.rows = rows, g.cols = cols;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const auto [from_row, from_col] = source(r, c);
      GridView v = grid.view(from_row, from_col);
      v.row = r, v.col = c;
      std::tie(v.x_mm, v.y_mm) = position(v.x_mm, v.y_mm);
      g.views[std::size_t(r * cols + c)] = v;
    }
  g.missing.clear();
  for (const GridView& v : g.views)
    if (v.file.empty()) g.missing.push_back(CameraLabel(v.row, v.col));
  return g;
}

}  // namespace

ImportedGrid WithAxesReversed(const ImportedGrid& grid, bool rows, bool cols) {
  return Rearranged(
      grid, grid.rows, grid.cols,
      [&](int r, int c) {
        return std::pair{rows ? grid.rows - 1 - r : r, cols ? grid.cols - 1 - c : c};
      },
      [&](double x, double y) {
        return std::pair{cols ? -x : x, rows ? -y : y};
      });
}

ImportedGrid WithAxesSwapped(const ImportedGrid& grid) {
  return Rearranged(
      grid, grid.cols, grid.rows,
      [&](int r, int c) {
        return std::pair{grid.rows - 1 - c, grid.cols - 1 - r};
      },
      [](double x, double y) {
        return std::pair{-y, -x};
      });
}

std::string ToString(AxesVerdict verdict) {
  switch (verdict) {
    case AxesVerdict::kAgree:
      return "agree";
    case AxesVerdict::kRowsReversed:
      return "rows-reversed";
    case AxesVerdict::kColsReversed:
      return "cols-reversed";
    case AxesVerdict::kBothReversed:
      return "both-reversed";
    case AxesVerdict::kSwapped:
      return "swapped";
    case AxesVerdict::kUndecided:
      break;
  }
  return "undecided";
}

std::string Describe(const ParallaxAxes& a) {
  const std::string measured =
      a.single_line ? fmt::format("{} points tracked from {}", a.points, a.views)
                    : fmt::format(
                          "{} points tracked from {}: correlation {:+.2f} between the parallax "
                          "along the row and along the column",
                          a.points, a.views, a.correlation);
  switch (a.verdict) {
    case AxesVerdict::kAgree:
      return "the views' parallax agrees with the names' axes (" + measured + ")";
    case AxesVerdict::kRowsReversed:
      return a.single_line
                 ? "the views' parallax runs against the names' rows: every point moves with "
                   "the camera, where parallel cameras see it move against it (" +
                       measured + ")"
                 : "the views' parallax along the columns runs against the names' rows (" +
                       measured + ")";
    case AxesVerdict::kColsReversed:
      return "the views' parallax along the rows runs against the names' columns: every point "
             "moves with the camera, where parallel cameras see it move against it (" +
             measured + ")";
    case AxesVerdict::kBothReversed:
      return "the views' parallax runs against both of the names' axes: every point moves with "
             "the camera, where parallel cameras see it move against it (" +
             measured + ")";
    case AxesVerdict::kSwapped:
      return a.single_line
                 ? fmt::format(
                       "the views along the named line move across it ({}): the names' row is "
                       "a column, or their column a row",
                       measured)
                 : fmt::format(
                       "the views along a named row move vertically and those along a named "
                       "column horizontally ({} points tracked from {}): the names' rows and "
                       "columns are exchanged",
                       a.points, a.views);
    case AxesVerdict::kUndecided:
      break;
  }
  return "the names' axes not checked against the views' parallax: " + a.why;
}

}  // namespace lfcam
