#include "lfcam/io/parallel_import.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"

namespace lfcam {

namespace fs = std::filesystem;

double HalfSample(int count, int samples_between_neighbours) {
  return count % 2 == 0 && samples_between_neighbours % 2 == 1 ? 0.5 : 0.0;
}

std::optional<std::pair<double, int>> WholeSampleStDistance(const ImportedGrid& g, double focal_px,
                                                            double distance_mm) {
  if (!(distance_mm > 0) || !(g.pitch_mm > 0) || !(focal_px > 0)) return std::nullopt;
  const double step = g.pitch_mm * focal_px / distance_mm;  // samples between neighbours
  const int n = std::max(1, int(std::lround(step)));
  const double snapped = g.pitch_mm * focal_px / n;
  double x_sum = 0, y_sum = 0;
  int present = 0;
  for (const GridView& v : g.views)
    if (!v.file.empty()) {
      x_sum += v.x_mm - v.col * g.pitch_mm;
      y_sum += v.y_mm - v.row * g.pitch_mm;
      ++present;
    }
  if (present == 0) return std::nullopt;
  const double cx = x_sum / present + 0.5 * (g.cols - 1) * g.pitch_mm;
  const double cy = y_sum / present + 0.5 * (g.rows - 1) * g.pitch_mm;
  for (const GridView& v : g.views) {
    if (v.file.empty()) continue;
    // With an even count and n odd the grid's centre lies half a sample off: the window moves.
    const double ox = (v.x_mm - cx) * focal_px / snapped + HalfSample(g.cols, n);
    const double oy = (v.y_mm - cy) * focal_px / snapped + HalfSample(g.rows, n);
    if (std::abs(ox - std::round(ox)) > 1e-3 || std::abs(oy - std::round(oy)) > 1e-3)
      return std::nullopt;  // not a regular grid: no distance puts every view on whole samples
  }
  return std::pair{snapped, n};
}

double EstimateDominantDepthMm(const fs::path& dir, const ImportedGrid& g, double focal_px) {
  // The two outermost views of the middle row, else of the middle column.
  const bool along_row = g.cols >= g.rows;
  const GridView* a = nullptr;
  const GridView* b = nullptr;
  const int n = along_row ? g.cols : g.rows;
  for (int i = 0; i < n && !a; ++i) {
    const GridView& v = along_row ? g.view(g.rows / 2, i) : g.view(i, g.cols / 2);
    if (!v.file.empty()) a = &v;
  }
  for (int i = n - 1; i >= 0 && !b; --i) {
    const GridView& v = along_row ? g.view(g.rows / 2, i) : g.view(i, g.cols / 2);
    if (!v.file.empty()) b = &v;
  }
  if (!a || !b || a == b)
    throw Error(
        fmt::format("{}: one view: give the st-plane's distance (--st-distance)", dir.string()));
  cv::Mat ga, gb;
  ReadImageGray8(dir / a->file).convertTo(ga, CV_32F);
  ReadImageGray8(dir / b->file).convertTo(gb, CV_32F);
  cv::Mat window;
  cv::createHanningWindow(window, ga.size(), CV_32F);
  const cv::Point2d shift = cv::phaseCorrelate(ga, gb, window);
  const double baseline = std::hypot(b->x_mm - a->x_mm, b->y_mm - a->y_mm);
  const double disparity = std::hypot(shift.x, shift.y);
  if (disparity < 0.5 || baseline <= 0)
    throw Error(
        fmt::format("{}: the views show no measurable disparity ({:.2f} px between {} "
                    "and {}): give the st-plane's distance (--st-distance)",
                    dir.string(), disparity, a->file, b->file));
  return focal_px * baseline / disparity;
}

ImportedSession MakeImportedSession(const fs::path& dir, const ImportedGrid& g,
                                    const ImportOptions& o) {
  ImportedSession s;
  // The intrinsics: a focal length in pixels, from the flags, the description or the names.
  const auto focal_mm = o.focal_mm ? o.focal_mm : g.focal_mm;
  const auto sensor_mm = o.sensor_width_mm ? o.sensor_width_mm : g.sensor_width_mm;
  if (o.focal_px)
    s.focal_px = *o.focal_px;
  else if (g.focal_px && !o.focal_mm)
    s.focal_px = *g.focal_px;
  else if (focal_mm && sensor_mm)
    s.focal_px = *focal_mm / *sensor_mm * g.width;
  else
    throw Error(
        fmt::format("{}: the views' focal length is not known: give --focal-px, or "
                    "--focal-mm and --sensor-width-mm",
                    dir.string()));
  if (!(s.focal_px > 0)) throw Error("the focal length must be positive");

  if (o.st_distance_mm) {
    s.st_distance_mm = *o.st_distance_mm;
  } else if (g.st_distance_mm) {
    s.st_distance_mm = *g.st_distance_mm;
  } else {
    s.st_distance_mm = EstimateDominantDepthMm(dir, g, s.focal_px);
    s.st_distance_estimated = true;
    if (const auto snapped = WholeSampleStDistance(g, s.focal_px, s.st_distance_mm)) {
      s.st_distance_unsnapped_mm = s.st_distance_mm;
      s.st_distance_mm = snapped->first;
      s.samples_between_neighbours = snapped->second;
    }
  }
  if (!(s.st_distance_mm > 0)) throw Error("the st distance must be positive");
  const double d = s.st_distance_mm;

  // The camera plane at z = d, x right, y up; the grid's corner half a pitch beyond its
  // outermost cameras (the centres are where the names say: `build` reads each camera at its
  // own centre).
  double x_min = 1e300, y_min = 1e300, x_sum = 0, y_sum = 0;
  int present = 0;
  for (const GridView& v : g.views)
    if (!v.file.empty()) {
      x_min = std::min(x_min, v.x_mm - v.col * g.pitch_mm);
      y_min = std::min(y_min, v.y_mm - v.row * g.pitch_mm);
      x_sum += v.x_mm - v.col * g.pitch_mm;
      y_sum += v.y_mm - v.row * g.pitch_mm;
      ++present;
    }
  // The grid's origin (camera (0, 0)'s ideal centre): the mean over the views.
  const double x0 = x_sum / present, y0 = y_sum / present;
  (void)x_min, (void)y_min;
  Slab slab;
  slab.uv.p_ca = Vec3(x0 - 0.5 * g.pitch_mm, y0 - 0.5 * g.pitch_mm, d);
  slab.uv.u_ca = Vec3::UnitX();
  slab.uv.v_ca = Vec3::UnitY();
  slab.uv.n_ca = Vec3::UnitZ();
  slab.uv.rows = g.rows;
  slab.uv.cols = g.cols;
  slab.uv.pitch_mm = g.pitch_mm;
  // The st window: what the grid's central (ideal) camera sees on the plane z = 0.
  const Vec3 centre = slab.uv.center();
  slab.st.width_mm = d * g.width / s.focal_px;
  slab.st.height_mm = d * g.height / s.focal_px;
  // Moved by half a sample where the grid's centre lies half a sample off the views' pixels.
  const double sample_mm = d / s.focal_px;
  slab.st.origin = Vec3(centre.x() - 0.5 * slab.st.width_mm +
                            sample_mm * HalfSample(g.cols, s.samples_between_neighbours),
                        centre.y() - 0.5 * slab.st.height_mm +
                            sample_mm * HalfSample(g.rows, s.samples_between_neighbours),
                        0);
  slab.st.x_axis = Vec3::UnitX();
  slab.st.y_axis = Vec3::UnitY();
  // The reference window is what the central camera sees; each view is built in its own window
  // (BuildOptions::view_windows: the reference moved by the camera's offset in whole samples), so
  // that together they cover what every camera saw and a render at any of the grid's cameras has
  // no band outside the st domain.
  slab.st_domain = {};
  slab.validate();

  CalibrationFile& cal = s.calibration;
  cal.rows = g.rows;
  cal.cols = g.cols;
  cal.width = g.width;
  cal.height = g.height;
  cal.slab = slab;
  const Mat3 rotation = WorldFromCameraRotation(slab.uv.u_ca, slab.uv.v_ca, slab.uv.n_ca);
  for (const GridView& v : g.views) {
    CalibratedCamera c;
    c.row = v.row;
    c.col = v.col;
    c.calibrated = !v.file.empty();
    if (!c.calibrated) c.reason = "not in the imported folder";
    c.intrinsics.width = g.width;
    c.intrinsics.height = g.height;
    c.intrinsics.fx = c.intrinsics.fy = s.focal_px;
    c.intrinsics.cx = 0.5 * (g.width - 1);
    c.intrinsics.cy = 0.5 * (g.height - 1);
    c.world_from_camera = {rotation, Vec3(v.x_mm, v.y_mm, d)};
    cal.cameras.push_back(std::move(c));
  }
  cal.summary = {{"import",
                  {{"naming", ToString(g.naming)},
                   {"folder", dir.string()},
                   {"focal_px", s.focal_px},
                   {"st_distance_mm", d},
                   {"st_distance_estimated", s.st_distance_estimated},
                   {"st_distance_estimate_mm", s.st_distance_unsnapped_mm.value_or(d)},
                   {"notes", NamingNotes(g)},
                   {"missing", g.missing}}}};

  CaptureManifest& m = s.manifest;
  m.rows = g.rows;
  m.cols = g.cols;
  m.pitch_mm = g.pitch_mm;
  m.sensor_width = g.width;
  m.sensor_height = g.height;
  m.sensor_model = "imported (" + ToString(g.naming) + ")";
  Shot scene(ShotKind::kScene, "scene");
  for (const GridView& v : g.views)
    if (!v.file.empty()) scene.images.push_back(ShotImage(v.row, v.col, v.file));
  m.shots.push_back(std::move(scene));
  m.source = cal.summary["import"];
  return s;
}

}  // namespace lfcam
