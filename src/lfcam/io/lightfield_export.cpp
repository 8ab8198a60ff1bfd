#include "lfcam/io/lightfield_export.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <utility>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/staged_folder.h"
#include "lfcam/core/view_filling.h"
#include "lfcam/io/sparse_points.h"

namespace lfcam {

namespace {

namespace fs = std::filesystem;

std::string ViewName(int row, int col) { return fmt::format("view_{:02d}_{:02d}.png", row, col); }

nlohmann::json MatrixToJson(const Mat3& r, const Vec3& t) {
  nlohmann::json m = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) m.push_back({r(i, 0), r(i, 1), r(i, 2), t(i)});
  m.push_back({0.0, 0.0, 0.0, 1.0});
  return m;
}

// An ASCII PLY of the points: x y z (world millimetres times `scale`), red green blue.
std::string PointCloudPly(const SparsePoints& points, double scale) {
  std::string text = fmt::format(
      "ply\nformat ascii 1.0\ncomment lfcam: points from the light field's depth maps\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n",
      points.points.size());
  for (const SparsePoint& p : points.points) {
    const Vec3 x = p.position_mm * scale;
    text += fmt::format("{:.7g} {:.7g} {:.7g} {} {} {}\n", x.x(), x.y(), x.z(), p.rgb[0], p.rgb[1],
                        p.rgb[2]);
  }
  return text;
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw Error(fmt::format("{}: cannot write", path.string()));
}

}  // namespace

cv::Mat ViewImage(const LightField& lf, int row, int col) {
  const auto& d = lf.dims();
  cv::Mat image(d.n_t, d.n_s, CV_8UC3);
  if (lf.sample_type() == SampleType::kSrgb8) {
    const cv::Mat view(d.n_t, d.n_s, CV_8UC3, const_cast<std::uint8_t*>(lf.view_data(row, col)));
    cv::flip(view, image, 0);
    return image;
  }
  cv::Mat linear(d.n_t, d.n_s, CV_32FC3);
  for (int l = 0; l < d.n_t; ++l)
    for (int k = 0; k < d.n_s; ++k) {
      const Eigen::Vector3f c = lf.linear_rgb(row, col, k, l);
      linear.at<cv::Vec3f>(d.n_t - 1 - l, k) = {c.x(), c.y(), c.z()};
    }
  return LinearToSrgb8Image(linear);
}

ExportFormat ExportFormatFromString(const std::string& name) {
  if (name == "png-views") return ExportFormat::kPngViews;
  if (name == "nerf") return ExportFormat::kNerf;
  if (name == "colmap") return ExportFormat::kColmap;
  throw UsageError(fmt::format("--format '{}' is not png-views, nerf, colmap or quilt", name));
}

ViewCamera ViewAsCamera(const LightField& lf, int row, int col) {
  const Slab& slab = lf.slab();
  const ViewWindow& st = slab.st;
  const Vec3 x_axis = st.x_axis.normalized();
  const Vec3 y_axis = (st.y_axis - st.y_axis.dot(x_axis) * x_axis).normalized();
  const Vec3 normal = x_axis.cross(y_axis);  // toward the cameras
  const Vec3 c = lf.camera_center(row, col);
  const double d = normal.dot(c - st.origin);  // the camera's height above the st-plane
  if (!(d > 0))
    throw Error(fmt::format("view ({}, {}): its camera is not in front of the st-plane", row, col));
  const auto& dims = lf.dims();
  const StSampling sampling = lf.st_sampling(row, col);       // the view's own window
  const double ds = sampling.ds_mm(), dt = sampling.dt_mm();  // mm a sample
  ViewCamera v;
  v.width = dims.n_s;
  v.height = dims.n_t;
  v.fx = d / ds;
  v.fy = d / dt;
  // Sample k sits at s_of(k) * width along x_axis from the origin; pixel u = k.
  const double x0 = x_axis.dot(st.origin - c) + sampling.s_of(0) * st.width_mm;
  const double y0 = y_axis.dot(st.origin - c) + sampling.t_of(0) * st.height_mm;
  v.cx = -v.fx * x0 / d;
  v.cy = dims.n_t - 1 + v.fy * y0 / d;
  Mat3 r;
  r.col(0) = x_axis;
  r.col(1) = -y_axis;
  r.col(2) = -normal;
  v.world_from_camera = {r, c};
  return v;
}

ExportReport ExportLightField(const LightField& lf, ExportFormat format, const fs::path& out_dir,
                              const DepthSet* depth) {
  if (depth && format == ExportFormat::kPngViews)
    throw Error(
        "depth maps are exported as points for COLMAP (--format colmap) or NeRF (--format nerf)");
  if (depth && !(depth->dims() == lf.dims()))
    throw Error("the depth maps are not of this light field (another grid or st resolution)");
  StagedFolder folder(out_dir);
  const fs::path& staging = folder.path();
  const fs::path& out = folder.out();
  std::error_code ec;
  const auto& d = lf.dims();
  const std::string image_folder = format == ExportFormat::kPngViews ? "views" : "images";
  fs::create_directories(staging / image_folder, ec);
  if (ec) throw Error(fmt::format("{}: cannot create: {}", staging.string(), ec.message()));

  ExportReport report;
  nlohmann::json views = nlohmann::json::array(), frames = nlohmann::json::array();
  std::string cameras_txt =
      "# Camera list with one line of data per camera:\n"
      "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n";
  std::string images_txt =
      "# Image list with two lines of data per image:\n"
      "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
      "#   POINTS2D[] as (X, Y, POINT3D_ID)\n";
  Vec3 centroid = Vec3::Zero();
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) centroid += lf.camera_center(r, c) / double(d.view_count());
  // NeRF's lengths: metres where lfcam's are millimetres; where the light field has no metric
  // scale (lengths in units of the cameras' spacing), those units as they are, so that the scene
  // keeps the size NeRF trainers expect (a thousandth of a unit apart, it would not).
  const bool metric = WorldLengthUnit(lf.metadata()) == "mm";
  const double nerf_per_world = metric ? 1e-3 : 1.0;
  double reach_nerf = 0;  // the farthest st-window corner from the cameras' centroid
  const StDomain all = lf.st_union();
  for (double s : {all.s0, all.s1})
    for (double t : {all.t0, all.t1})
      reach_nerf =
          std::max(reach_nerf, (lf.slab().st.point_at(s, t) - centroid).norm() * nerf_per_world);

  const SparsePoints points = depth ? PointsFromDepth(lf, *depth) : SparsePoints{};
  // A view filled from its neighbours (a camera without an image, a black view) is no
  // photograph: the grid of PNG views keeps it, marked, and COLMAP and NeRF, which would take it
  // for one, are not given it. Each view keeps its id (row * cols + col + 1) either way.
  const std::vector<bool> photographed = PhotographedViews(lf);
  int id = 0;
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) {
      ++id;
      const bool is_filled = !photographed[std::size_t(id - 1)];
      if (is_filled && format != ExportFormat::kPngViews) {
        report.filled_left_out.emplace_back(r, c);
        continue;
      }
      ++report.views;
      const std::string name = ViewName(r, c);
      WriteImage(staging / image_folder / name, ViewImage(lf, r, c));
      const ViewCamera v = ViewAsCamera(lf, r, c);
      const Mat3& rot = v.world_from_camera.rotation;
      const Vec3& centre = v.world_from_camera.translation;
      views.push_back({{"row", r},
                       {"col", c},
                       {"file", image_folder + "/" + name},
                       {"center_mm", {centre.x(), centre.y(), centre.z()}},
                       {"width", v.width},
                       {"height", v.height},
                       {"fx", v.fx},
                       {"fy", v.fy},
                       {"cx", v.cx},
                       {"cy", v.cy},
                       {"world_from_camera", MatrixToJson(rot, centre)}});
      if (is_filled) views.back()["filled"] = true;
      // NeRF: camera-to-world with OpenGL's axes (x right, y up, z back), metres (or units).
      Mat3 gl = rot;
      gl.col(1) = -rot.col(1);
      gl.col(2) = -rot.col(2);
      frames.push_back({{"file_path", image_folder + "/" + name},
                        {"transform_matrix", MatrixToJson(gl, centre * nerf_per_world)},
                        {"fl_x", v.fx},
                        {"fl_y", v.fy},
                        {"cx", v.cx + 0.5},
                        {"cy", v.cy + 0.5},
                        {"w", v.width},
                        {"h", v.height}});
      // COLMAP: world-to-camera, Hamilton quaternion (w, x, y, z); pixel corners at integers.
      const Mat3 camera_from_world = rot.transpose();
      const Eigen::Quaterniond q(camera_from_world);
      const Vec3 t = -(camera_from_world * centre);
      cameras_txt += fmt::format("{} PINHOLE {} {} {:.17g} {:.17g} {:.17g} {:.17g}\n", id, v.width,
                                 v.height, v.fx, v.fy, v.cx + 0.5, v.cy + 0.5);
      images_txt +=
          fmt::format("{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {} {}\n", id,
                      q.w(), q.x(), q.y(), q.z(), t.x(), t.y(), t.z(), id, name);
      // Its points: X, Y, POINT3D_ID (ids from 1).
      if (depth) {
        std::string line;
        for (const SparseObservation& o : points.observations[std::size_t(id - 1)])
          line += fmt::format("{}{:.3f} {:.3f} {}", line.empty() ? "" : " ", o.x, o.y, o.point + 1);
        images_txt += line;
        report.observations += points.observations[std::size_t(id - 1)].size();
      }
      images_txt += "\n";
    }

  if (format == ExportFormat::kPngViews) {
    report.main_file = out / "cameras.json";
    WriteText(staging / "cameras.json",
              JsonToText({{"format", "lfcam-views-export"},
                          {"version", 1},
                          {"rows", d.rows},
                          {"cols", d.cols},
                          {"units", metric ? "mm, lfcam's world frame (docs/conventions.md)"
                                           : "units of the cameras' spacing (no metric scale "
                                             "was known), lfcam's world frame "
                                             "(docs/conventions.md)"},
                          {"camera_convention",
                           "OpenCV: x right, y down, z forward; pixel (0, 0) "
                           "the centre of the top-left pixel"},
                          {"views", views}},
                         2) +
                  "\n");
  } else if (format == ExportFormat::kNerf) {
    report.main_file = out / "transforms.json";
    const ViewCamera centre = ViewAsCamera(lf, d.rows / 2, d.cols / 2);
    int aabb = 1;
    while (aabb < 128 && aabb < reach_nerf) aabb *= 2;
    nlohmann::json transforms = {{"camera_model", "OPENCV"},
                                 {"fl_x", centre.fx},
                                 {"fl_y", centre.fy},
                                 {"cx", centre.cx + 0.5},
                                 {"cy", centre.cy + 0.5},
                                 {"w", centre.width},
                                 {"h", centre.height},
                                 {"k1", 0.0},
                                 {"k2", 0.0},
                                 {"p1", 0.0},
                                 {"p2", 0.0},
                                 {"aabb_scale", aabb}};
    if (depth) {
      // nerfstudio's own key: the points its Gaussian splatting starts from, in the frames' world
      // frame (metres).
      transforms["ply_file_path"] = "sparse_pc.ply";
      WriteText(staging / "sparse_pc.ply", PointCloudPly(points, nerf_per_world));
      report.points = int(points.points.size());
    }
    transforms["frames"] = frames;
    WriteText(staging / "transforms.json", JsonToText(transforms, 2) + "\n");
  } else {
    report.main_file = out / "sparse/0/images.txt";
    fs::create_directories(staging / "sparse/0", ec);
    WriteText(staging / "sparse/0/cameras.txt",
              cameras_txt + fmt::format("# Number of cameras: {}\n", report.views));
    WriteText(staging / "sparse/0/images.txt", images_txt);
    std::string points_txt = fmt::format(
        "# 3D point list with one line of data per point:\n"
        "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
        "# Number of points: {}\n",
        points.points.size());
    for (std::size_t i = 0; i < points.points.size(); ++i) {
      const SparsePoint& p = points.points[i];
      // The error is 0: the poses are known, not estimated from these points.
      points_txt += fmt::format("{} {:.4f} {:.4f} {:.4f} {} {} {} 0", i + 1, p.position_mm.x(),
                                p.position_mm.y(), p.position_mm.z(), p.rgb[0], p.rgb[1], p.rgb[2]);
      for (const auto& [view, index] : p.track)
        points_txt += fmt::format(" {} {}", view + 1, index);
      points_txt += "\n";
    }
    report.points = int(points.points.size());
    WriteText(staging / "sparse/0/points3D.txt", points_txt);
  }
  folder.Commit();
  return report;
}

}  // namespace lfcam
