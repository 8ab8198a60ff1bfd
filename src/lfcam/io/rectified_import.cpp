#include "lfcam/io/rectified_import.h"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <opencv2/core.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/least_squares.h"
#include "lfcam/core/view_filling.h"

namespace lfcam {

namespace fs = std::filesystem;

Vec2 RectifiedGeometry::PrincipalPoint(double x_mm, double y_mm) const {
  const double k = focal_px / zero_disparity_mm;
  return reference_principal_point +
         k * Vec2(x_mm - reference_xy_mm.x(), -(y_mm - reference_xy_mm.y()));
}

double RectifiedGeometry::DisparityOfDepth(double depth_mm) const {
  return focal_px * pitch_mm * (1.0 / depth_mm - 1.0 / zero_disparity_mm);
}

namespace {

// Where a view's camera sits: the named position, or the index position at the chosen pitch.
Vec2 ViewPosition(const ImportedGrid& g, const GridView& v, double pitch_mm) {
  const double scale = g.positions_known ? 1.0 : pitch_mm / g.pitch_mm;
  return {v.x_mm * scale, v.y_mm * scale};
}

// The grid's ideal origin (camera (0, 0)'s centre): the mean over the present views.
Vec2 GridOrigin(const ImportedGrid& g, double pitch_mm) {
  Vec2 sum = Vec2::Zero();
  int n = 0;
  for (const GridView& v : g.views)
    if (!v.file.empty()) {
      sum += ViewPosition(g, v, pitch_mm) - pitch_mm * Vec2(v.col, v.row);
      ++n;
    }
  return sum / std::max(n, 1);
}

// parameters.cfg's focal length in pixels counts its own image size; views of another size (a
// copy resized since) are the same sensor in other pixels, so the focal length scales with them,
// and is said. Another aspect ratio is not a resize: refused.
double FocalPxOfTheViews(const ImportedGrid& g, double focal_px, std::vector<std::string>& notes) {
  if (!g.hci || !g.hci->width_px || !g.hci->height_px) return focal_px;
  const int w = *g.hci->width_px, h = *g.hci->height_px;
  if (w == g.width && h == g.height) return focal_px;
  if (std::abs(double(w) * g.height - double(h) * g.width) > 0.01 * double(w) * g.height)
    throw Error(fmt::format(
        "{}: gives the views as {}x{}, but they are {}x{}: another aspect ratio, so its focal "
        "length does not apply to them (--focal-px sets one)",
        g.hci->source, w, h, g.width, g.height));
  const double scaled = focal_px * std::max(g.width, g.height) / std::max(w, h);
  notes.push_back(fmt::format(
      "parameters.cfg gives the views as {}x{}, but they are {}x{}: its focal length, {:.1f} px "
      "at its size, scaled to theirs: {:.1f} px",
      w, h, g.width, g.height, focal_px, scaled));
  return scaled;
}

// Where the views show the scene, in px of disparity between neighbours: twice the parallax
// tracked in them, joined to parameters.cfg's disparity range (at the views' size) widened by
// half its span, since a published range may fall short (antinous' "about +-2 px" reaches
// -3.1 .. +2.7).
std::optional<std::array<double, 2>> SceneDisparityPx(const ImportedGrid& g,
                                                      const ImportOptions& o) {
  std::optional<std::array<double, 2>> bracket;
  const auto join = [&](double farthest, double nearest) {
    if (!bracket) bracket = std::array{0.0, 0.0};
    (*bracket)[0] = std::min((*bracket)[0], farthest);
    (*bracket)[1] = std::max((*bracket)[1], nearest);
  };
  if (o.scene_parallax_px && *o.scene_parallax_px > 0 && std::isfinite(*o.scene_parallax_px)) {
    const double d = SceneBracketPx(*o.scene_parallax_px);
    join(-d, d);
  }
  if (g.hci && g.hci->disp_min && g.hci->disp_max && *g.hci->disp_min < *g.hci->disp_max) {
    const double scale =
        g.hci->width_px && g.hci->height_px
            ? double(std::max(g.width, g.height)) / std::max(*g.hci->width_px, *g.hci->height_px)
            : 1.0;
    const double lo = *g.hci->disp_min * scale, hi = *g.hci->disp_max * scale;
    const double margin = 0.5 * (hi - lo);
    join(lo - margin, hi + margin);
  }
  return bracket;
}

}  // namespace

double SceneBracketPx(double parallax_px) { return std::max(1.0, std::ceil(2 * parallax_px)); }

RectifiedGeometry ResolveRectifiedGeometry(const ImportedGrid& g, const ImportOptions& o) {
  RectifiedGeometry r;
  const std::string units = g.positions_known || o.pitch_mm ? "mm" : "units";
  // The pitch: named positions, parameters.cfg or the flag; else unit.
  if (o.pitch_mm && g.positions_known)
    throw Error(fmt::format("the {} views give their positions: --pitch-mm does not apply",
                            ToString(g.naming)));
  r.pitch_mm = o.pitch_mm.value_or(g.pitch_mm);
  r.metric = g.positions_known || o.pitch_mm.has_value();
  r.notes = NamingNotes(g);
  if (!g.positions_known && !o.pitch_mm)
    r.assumed.push_back(fmt::format(
        "the cameras 1 unit apart (the names give grid indices only; --pitch-mm sets it)"));

  // The focal length in pixels.
  const auto focal_mm = o.focal_mm ? o.focal_mm : g.focal_mm;
  const auto sensor_mm = o.sensor_width_mm ? o.sensor_width_mm : g.sensor_width_mm;
  if (o.focal_px) {
    r.focal_px = *o.focal_px;
  } else if (g.focal_px && !o.focal_mm) {
    r.focal_px = FocalPxOfTheViews(g, *g.focal_px, r.notes);
  } else if (focal_mm && sensor_mm) {
    r.focal_px = *focal_mm / *sensor_mm * g.width;
  } else {
    r.focal_px = std::max(g.width, g.height);
    r.assumed.push_back(fmt::format(
        "a focal length of {} px (the larger image side; {:.1f} degrees across the width): no "
        "focal length is published (--focal-px sets it)",
        r.focal_px, 2.0 * std::atan(0.5 * g.width / r.focal_px) * 180.0 / M_PI));
  }
  if (!(r.focal_px > 0) || !std::isfinite(r.focal_px))
    throw Error("the focal length must be positive");

  const Vec2 origin = GridOrigin(g, r.pitch_mm);
  r.reference_xy_mm = origin + 0.5 * r.pitch_mm * Vec2(g.cols - 1, g.rows - 1);
  r.reference_principal_point = {0.5 * (g.width - 1), 0.5 * (g.height - 1)};

  // The zero-disparity plane.
  const bool principal_points = !g.views.empty() && g.views.front().principal_point.has_value();
  if (o.st_distance_mm) {
    r.zero_disparity_mm = *o.st_distance_mm;
  } else if (g.zero_disparity_mm) {
    r.zero_disparity_mm = *g.zero_disparity_mm;
  } else if (g.st_distance_mm) {
    r.zero_disparity_mm = *g.st_distance_mm;
  } else if (principal_points) {
    // cx = a + k x, cy = b - k y with k = f / Z0, by least squares over the views.
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * long(g.views.size()), 3);
    Eigen::VectorXd rhs(2 * long(g.views.size()));
    for (std::size_t i = 0; i < g.views.size(); ++i) {
      const Vec2 xy = ViewPosition(g, g.views[i], r.pitch_mm) - r.reference_xy_mm;
      A(2 * long(i), 0) = 1, A(2 * long(i), 2) = xy.x();
      A(2 * long(i) + 1, 1) = 1, A(2 * long(i) + 1, 2) = -xy.y();
      rhs(2 * long(i)) = g.views[i].principal_point->x();
      rhs(2 * long(i) + 1) = g.views[i].principal_point->y();
    }
    const Eigen::Vector3d x = SolveLeastSquares(A, rhs);
    const Eigen::VectorXd residual = A * x - rhs;
    long worst = 0;
    const double worst_px = residual.cwiseAbs().maxCoeff(&worst);
    if (worst_px > 0.05) {
      const GridView& v = g.views[std::size_t(worst / 2)];
      throw Error(fmt::format(
          "the views' principal points do not fit one zero-disparity plane: {} ({}) is {:.3f} px "
          "off (a rectified rig shifts each camera's principal point by f b / Z0)",
          CameraLabel(v.row, v.col), v.file, worst_px));
    }
    if (!(x(2) > 1e-9))
      throw Error(fmt::format(
          "the views' principal points {}: not a rectified rig in front of the cameras (a "
          "parallel rig: say \"rig\": \"parallel\")",
          std::abs(x(2)) <= 1e-9 ? "do not move from camera to camera"
                                 : "move the wrong way (the zero-disparity plane would lie "
                                   "behind the cameras)"));
    r.reference_principal_point = {x(0), x(1)};
    r.zero_disparity_mm = r.focal_px / x(2);
  } else {
    const double behind = o.infinity_disparity_px.value_or(kAssumedInfinityDisparityPx);
    r.zero_disparity_mm = r.focal_px * r.pitch_mm / behind;
    r.assumed.push_back(fmt::format(
        "the zero-disparity plane {:.4g} {} from the cameras, so that infinity lies {} px of "
        "disparity behind it (no distance is published; --st-distance sets it){}; disparities "
        "are as photographed, distances in these units",
        r.zero_disparity_mm, units, behind,
        o.infinity_disparity_px
            ? fmt::format(", twice the largest parallax the views show between neighbours")
            : std::string()));
  }
  if (!(r.zero_disparity_mm > 0) || !std::isfinite(r.zero_disparity_mm))
    throw Error("the zero-disparity plane's distance must be positive");
  // A distance given or published that puts infinity nearer, in disparity, than the parallax the
  // views show: what lies farther behind the zero-disparity plane than infinity cannot be swept,
  // and if the scene does, its occlusions may then read the rig as turned half a turn.
  const double infinity_px = r.focal_px * r.pitch_mm / r.zero_disparity_mm;
  const bool distance_known =
      o.st_distance_mm || g.zero_disparity_mm || g.st_distance_mm || principal_points;
  if (distance_known && o.scene_parallax_px && *o.scene_parallax_px > infinity_px)
    r.notes.push_back(fmt::format(
        "the views show parallax of up to {:.1f} px between neighbours, and at this distance "
        "infinity lies {:.1f} px behind the zero-disparity plane: nothing can lie farther behind "
        "it than that. If the scene does (its depth wrong behind that plane, or the rig taken as "
        "turned below), the distance is too large",
        *o.scene_parallax_px, infinity_px));
  r.scene_disparity_px = SceneDisparityPx(g, o);
  return r;
}

LightField ImportRectifiedViews(const fs::path& dir, const ImportedGrid& g,
                                const RectifiedGeometry& geo,
                                const std::function<void()>& view_done,
                                RectifiedImportReport* report, bool fill_dark_views) {
  const auto start = std::chrono::steady_clock::now();
  const int W = g.width, H = g.height;
  const double z0 = geo.zero_disparity_mm, f = geo.focal_px, pitch = geo.pitch_mm;
  const Vec2 origin = GridOrigin(g, pitch);

  Slab slab;
  slab.uv.p_ca = Vec3(origin.x() - 0.5 * pitch, origin.y() - 0.5 * pitch, z0);
  slab.uv.u_ca = Vec3::UnitX();
  slab.uv.v_ca = Vec3::UnitY();
  slab.uv.n_ca = Vec3::UnitZ();
  slab.uv.rows = g.rows;
  slab.uv.cols = g.cols;
  slab.uv.pitch_mm = pitch;
  // The window every camera maps onto its pixels: pixel edges -0.5 and W - 0.5 (H - 0.5 at the
  // bottom, y down) of the reference camera, on the plane z = 0.
  const Vec2 ref = geo.reference_xy_mm, pp = geo.reference_principal_point;
  slab.st.width_mm = W * z0 / f;
  slab.st.height_mm = H * z0 / f;
  slab.st.origin =
      Vec3(ref.x() - (pp.x() + 0.5) * z0 / f, ref.y() - (H - 0.5 - pp.y()) * z0 / f, 0);
  slab.st.x_axis = Vec3::UnitX();
  slab.st.y_axis = Vec3::UnitY();
  slab.st_domain = {};
  slab.validate();

  LightField lf({g.rows, g.cols, W, H}, SampleType::kSrgb8, slab);
  const Mat3 rotation = WorldFromCameraRotation(slab.uv.u_ca, slab.uv.v_ca, slab.uv.n_ca);
  std::vector<ViewPose> poses(g.views.size());
  const std::size_t row_bytes = std::size_t(W) * 3;
  std::mutex progress;
  tbb::parallel_for(std::size_t(0), g.views.size(), [&](std::size_t i) {
    const GridView& v = g.views[i];
    const Vec2 xy =
        v.file.empty() ? Vec2(origin + pitch * Vec2(v.col, v.row)) : ViewPosition(g, v, pitch);
    const Vec2 c = geo.PrincipalPoint(xy.x(), xy.y());
    poses[i] = {Vec3(xy.x(), xy.y(), z0), rotation, CameraIntrinsics{W, H, f, f, c.x(), c.y(), {}}};
    if (v.file.empty()) return;
    const cv::Mat image = ReadImageSrgb8(dir / v.file);
    if (image.cols != W || image.rows != H)
      throw Error(fmt::format("{}: {}x{}, but the views are {}x{}", (dir / v.file).string(),
                              image.cols, image.rows, W, H));
    std::uint8_t* out = lf.mutable_view_data(v.row, v.col);
    for (int y = 0; y < H; ++y)
      std::memcpy(out + std::size_t(H - 1 - y) * row_bytes, image.ptr<std::uint8_t>(y), row_bytes);
    if (view_done) {
      const std::lock_guard lock(progress);
      view_done();
    }
  });

  // Missing views and views too dark to be photographs of the scene: the mean of the nearest
  // present ones, in linear light.
  RectifiedImportReport r;
  std::vector<bool> present;
  for (const GridView& v : g.views) present.push_back(!v.file.empty());
  nlohmann::json dark = nlohmann::json::array();
  for (const auto& [row, col] :
       fill_dark_views ? DarkViews(lf, present) : std::vector<std::pair<int, int>>{}) {
    const std::size_t i = std::size_t(row * g.cols + col);  // g.views is row-major
    const GridView& v = g.views[i];
    present[i] = false;
    r.dark.push_back(fmt::format("{} ({}, {})", v.file, v.row, v.col));
    dark.push_back({{"row", v.row}, {"col", v.col}, {"file", v.file}});
  }
  nlohmann::json filled = nlohmann::json::array();
  for (std::size_t i = 0; i < g.views.size(); ++i) {
    if (present[i]) continue;
    const GridView& v = g.views[i];
    const auto from = NearestPresentViews(g.rows, g.cols, present, v.row, v.col);
    FillViewWithMean(lf, v.row, v.col, from);
    r.filled.push_back(FilledViewLabel(v.row, v.col, from));
    filled.push_back({{"row", v.row}, {"col", v.col}, {"from", from}});
    if (view_done && v.file.empty()) view_done();  // a dark one was counted as read
  }
  lf.set_measured_poses(std::move(poses));

  const auto now = std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now());
  lf.metadata() = {{"source", "imported"},
                   {"import",
                    {{"folder", dir.string()},
                     {"naming", ToString(g.naming)},
                     {"rig", ToString(RigModel::kRectified)},
                     {"focal_px", f},
                     {"zero_disparity_distance_mm", z0},
                     {"st_distance_mm", z0},
                     {"pitch_mm", pitch},
                     {"units", geo.assumed.empty() ? "mm" : "assumed (see assumed)"},
                     {"length_unit", geo.metric ? "mm" : "units"},
                     {"assumed", geo.assumed},
                     {"notes", geo.notes},
                     {"stored", "sample for sample (each view's own pixels)"},
                     {"missing", g.missing},
                     {"filled_views", filled},
                     {"dark_views", dark},
                     {"ignored", g.ignored}}},
                   {"created", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", now)}};
  if (geo.scene_disparity_px)
    lf.metadata()["import"]["scene_disparity_px"] = *geo.scene_disparity_px;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report) *report = r;
  return lf;
}

}  // namespace lfcam
