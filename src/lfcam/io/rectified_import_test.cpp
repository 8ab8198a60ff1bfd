// Rectified (shifted-sensor) rigs against a synthetic rig whose truth is known: the paper scene
// photographed by the simulator through cameras whose principal points are shifted so that the
// plane 3.6 m away has zero disparity, named by indices alone (plenoptic style, no metric
// geometry) and described metrically. Then the real data sets in ../shared/data when present:
// the HCI benchmark scene against its true disparity, the Lytro views, as-camera renders.
#include "lfcam/io/rectified_import.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/io/lightfield_export.h"
#include "lfcam/render/rig_camera.h"
#include "lfcam/sim/board_radiance.h"
#include "lfcam/sim/camera_module.h"
#include "lfcam/sim/scene.h"

namespace lfcam::rectified_import_test {
namespace {

namespace fs = std::filesystem;

constexpr int kN = 5;  // cameras a side
constexpr int kWidth = 160, kHeight = 120;
constexpr double kFocalPx = 300;
constexpr double kPitchMm = 100;
constexpr double kZeroDisparityMm = 3600;  // the paper scene's world board

struct TrueRig {
  Scene scene = MakePaperScene();
  std::vector<SimulatedModule> modules;  // row-major, lfcam's rows (row 0 at the bottom)
};

// The rig's camera at lfcam grid (row, col): parallel, looking along -n_ca from the array's
// centre plus the grid offset, the sensor shifted so that the board plane has zero disparity.
SimulatedModule TrueCamera(const Scene& scene, int row, int col) {
  const ArrayPlane& a = scene.rig.array;
  SimulatedModule m;
  m.row = row, m.col = col;
  const double bx = (col - 0.5 * (kN - 1)) * kPitchMm, by = (row - 0.5 * (kN - 1)) * kPitchMm;
  m.world_from_camera = {WorldFromCameraRotation(a.u_ca, a.v_ca, a.n_ca),
                         a.center() + bx * a.u_ca + by * a.v_ca};
  m.intrinsics = {kWidth,
                  kHeight,
                  kFocalPx,
                  kFocalPx,
                  0.5 * (kWidth - 1) + kFocalPx * bx / kZeroDisparityMm,
                  0.5 * (kHeight - 1) - kFocalPx * by / kZeroDisparityMm,
                  {}};
  return m;
}

// Photographs every camera into a fresh folder as NAME_RR_CC.png (row 01 at the top).
fs::path WriteRectifiedRig(const std::string& name, TrueRig* rig) {
  const fs::path dir = fs::temp_directory_path() / (name + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  ExposureOptions exposure;
  exposure.noise = false;
  for (int r = 0; r < kN; ++r)
    for (int c = 0; c < kN; ++c) {
      const SimulatedModule m = TrueCamera(rig->scene, r, c);
      rig->modules.push_back(m);
      const cv::Mat rgb =
          ExposeModule(m, ModuleRayDirections(m), SceneRadiance(rig->scene, 2), exposure);
      cv::Mat bgr;
      cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
      cv::imwrite((dir / fmt::format("scene_{:02d}_{:02d}.png", kN - r, c + 1)).string(), bgr);
    }
  return dir;
}

// Where the imported geometry puts a point of view `ref`'s pixel (x, y) that has disparity d:
// the point on the pixel's ray at the depth the geometry gives d, projected into view (row,
// col) with that view's recorded camera.
Vec2 WarpByDisparity(const LightField& lf, const RectifiedGeometry& geo, int ref_row, int ref_col,
                     Vec2 pixel, double d, int row, int col) {
  const ViewPose& ref = lf.measured_poses()[std::size_t(ref_row * lf.dims().cols + ref_col)];
  const ViewPose& to = lf.measured_poses()[std::size_t(row * lf.dims().cols + col)];
  const Vec3 ray = ref.orientation * *ref.intrinsics->Unproject(pixel);
  // Depth Z (along -n_ca) of disparity d: d = f B (1/Z - 1/Z0).
  const double z = 1.0 / (d / (geo.focal_px * geo.pitch_mm) + 1.0 / geo.zero_disparity_mm);
  const Vec3 point = ref.center + ray * (z / -ray.z());
  return *to.intrinsics->Project(to.orientation.transpose() * (point - to.center));
}

TEST(RectifiedImport, IndexNamedViewsImportSampleForSampleWithTheTrueDisparityLaw) {
  TrueRig rig;
  const fs::path dir = WriteRectifiedRig("lfcam_rectified_unit_", &rig);
  const ImportedGrid grid = ScanGridFolder(dir, false);
  EXPECT_EQ(grid.naming, GridNaming::kUnitGrid);
  EXPECT_EQ(grid.rig, RigModel::kRectified);
  ASSERT_EQ(grid.rows, kN);
  EXPECT_EQ(grid.view(0, 0).file, fmt::format("scene_{:02d}_01.png", kN));  // bottom left
  const RectifiedGeometry geo = ResolveRectifiedGeometry(grid, {});
  EXPECT_EQ(geo.assumed.size(), 3u);  // pitch, focal length, zero-disparity plane
  const LightField lf = ImportRectifiedViews(dir, grid, geo);
  // Every view is its photograph, sample for sample (st rows bottom-up).
  for (int r = 0; r < kN; ++r)
    for (int c = 0; c < kN; ++c) {
      const cv::Mat photo = ReadImageSrgb8(dir / grid.view(r, c).file);
      for (int y = 0; y < kHeight; y += 7)
        ASSERT_EQ(std::memcmp(photo.ptr(y), lf.view_data(r, c) + (kHeight - 1 - y) * kWidth * 3,
                              kWidth * 3),
                  0)
            << r << "," << c << " row " << y;
    }
  // The geometry, whatever units were assumed, moves a scene point between views as the true
  // rig does: its true disparity, warped by the imported geometry, lands where the true camera
  // sees that point.
  const SimulatedModule& ref = rig.modules[std::size_t(2 * kN + 2)];
  double worst = 0;
  for (int y = 5; y < kHeight; y += 23)
    for (int x = 5; x < kWidth; x += 29) {
      const Vec3 ray = ref.world_from_camera.rotation * *ref.intrinsics.Unproject(Vec2(x, y));
      const double t = rig.scene.FirstHitDistance({ref.world_from_camera.translation, ray});
      ASSERT_TRUE(std::isfinite(t));
      const Vec3 point = ref.world_from_camera.translation + t * ray;
      const double depth = rig.scene.rig.array.n_ca.dot(ref.world_from_camera.translation - point);
      const double d = kFocalPx * kPitchMm * (1 / depth - 1 / kZeroDisparityMm);
      for (const auto& [r, c] : {std::pair{0, 0}, {4, 1}, {2, 3}, {4, 4}}) {
        const SimulatedModule& m = rig.modules[std::size_t(r * kN + c)];
        const Vec2 truth = *m.intrinsics.Project(m.world_from_camera.inverse() * point);
        const Vec2 warped = WarpByDisparity(lf, geo, 2, 2, Vec2(x, y), d, r, c);
        worst = std::max(worst, (truth - warped).norm());
      }
    }
  EXPECT_LT(worst, 1e-6);

  // As one of its cameras, the light field reproduces that camera's photograph exactly; between
  // cameras, the rig's camera there (its centre and shifted principal point).
  const VirtualCamera at = VirtualCamera(RigCameraParams(lf, 1, 3));
  const ViewPose& p13 = lf.measured_poses()[1 * kN + 3];
  const Vec3 expected = p13.orientation * *p13.intrinsics->Unproject(Vec2(17, 99));
  const Vec3 got = at.direction_through(17 + 0.5, kHeight - 99 - 0.5);
  EXPECT_LT((got.normalized() - expected.normalized()).norm(), 1e-9);
  EXPECT_LT((at.e_c() - p13.center).norm(), 1e-9);
  const VirtualCameraParams between = RigCameraParams(lf, 1.5, 3.25);
  EXPECT_NEAR(between.eye.x() - p13.center.x(), 0.25 * geo.pitch_mm, 1e-9);
  EXPECT_NEAR(between.eye.y() - p13.center.y(), 0.5 * geo.pitch_mm, 1e-9);
  EXPECT_THROW(RigCameraParams(lf, -0.5, 0), Error);
  EXPECT_THROW(RigCameraParams(lf, 0, kN - 0.9), Error);
  // Exported (COLMAP, NeRF, PNG views), each view's camera is the rig's: its shifted principal
  // point, its focal length.
  for (const auto& [r, c] : {std::pair{0, 0}, {1, 3}, {4, 2}}) {
    const ViewCamera v = ViewAsCamera(lf, r, c);
    const CameraIntrinsics& k = *lf.measured_poses()[std::size_t(r * kN + c)].intrinsics;
    EXPECT_NEAR(v.cx, k.cx, 1e-6) << r << "," << c;
    EXPECT_NEAR(v.cy, k.cy, 1e-6) << r << "," << c;
    EXPECT_NEAR(v.fx, k.fx, 1e-6);
  }

  // Through the command: the photograph itself at a camera; flags the rig's camera sets, a
  // position off the grid, a light field that records no cameras: refused, saying why.
  const fs::path outputs = dir.string() + "_out";
  fs::create_directories(outputs);
  const std::string file = (outputs / "rig.lf").string(), out = (outputs / "as.png").string();
  WriteLightField(lf, file);
  auto run = testing::Lfcam(fmt::format("render {} --as-camera 3,1 --out {} --quiet", file, out));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(
      cv::norm(cv::imread(out), cv::imread((dir / grid.view(3, 1).file).string()), cv::NORM_INF),
      0);
  // With no camera flags an imported light field renders as its central camera (not the
  // paper's f 500 mm at 4000 mm: another rig, another scene) and says so; --focal-length asks for
  // the paper's camera.
  run = testing::Lfcam(fmt::format("render {} --out {} --quiet", file, out));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("the rig's central camera (--as-camera 2,2)"), std::string::npos)
      << run.output;
  EXPECT_EQ(
      cv::norm(cv::imread(out), cv::imread((dir / grid.view(2, 2).file).string()), cv::NORM_INF),
      0);
  run = testing::Lfcam(fmt::format("render {} --focal-length 40 --out {} --quiet", file, out));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(run.output.find("central camera"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("f 40 mm"), std::string::npos) << run.output;
  // No scale was known, so its lengths are in units of the cameras' spacing, and every command
  // says so instead of "mm"; with --pitch-mm they are millimetres.
  EXPECT_EQ(WorldLengthUnit(lf.metadata()), "units");
  EXPECT_NE(run.output.find(" units, d_l 0 units,"), std::string::npos) << run.output;
  // Refocused nearer than the paper's f 500 mm, which the rig's camera does not have (refused
  // before: "must exceed the focal length (500 mm)", the scene 36 units away out of reach).
  run = testing::Lfcam(
      fmt::format("render {} --focus-distance 30 --aperture 2 --out {} --quiet", file, out));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("d_o 30 units"), std::string::npos) << run.output;
  // An aperture of 2 units (twice the cameras' spacing) is sampled as 56 mm would be on the
  // paper's 28-mm array, γ 4: 15 lens samples, not the 1 that 2 mm would get (a pinhole).
  EXPECT_NE(run.output.find("15 lens samples"), std::string::npos) << run.output;
  EXPECT_DOUBLE_EQ(LensLengthScale(lf), 28.0);
  // A quilt of it says its baseline and its plane of zero parallax in those units too.
  run = testing::Lfcam(
      fmt::format("export {} --format quilt --out {}", file, (outputs / "quilt").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find(" units, zero parallax at "), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(" mm"), std::string::npos) << run.output;
  run = testing::Lfcam("info " + file);
  EXPECT_NE(run.output.find("in units of the cameras' spacing, not mm"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("plane gap"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(" mm\n"), std::string::npos) << run.output;
  // Its depth map says so too: in the command's words and in the file.
  const fs::path depth_png = outputs / "depth.png";
  run = testing::Lfcam(fmt::format("depth {} --out {} --quiet", file, depth_png.string()));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find(" units, "), std::string::npos) << run.output;
  std::ifstream depth_in(depth_png, std::ios::binary);
  const std::string depth_bytes((std::istreambuf_iterator<char>(depth_in)), {});
  EXPECT_NE(depth_bytes.find("\"length_unit\":\"units\""), std::string::npos);
  ImportOptions metric;
  metric.pitch_mm = 2.0;
  const RectifiedGeometry metric_geo = ResolveRectifiedGeometry(grid, metric);
  EXPECT_TRUE(metric_geo.metric);
  EXPECT_FALSE(geo.metric);
  EXPECT_EQ(WorldLengthUnit(ImportRectifiedViews(dir, grid, metric_geo).metadata()), "mm");
  // At twice its size the same field of view: brought back to the photograph's size, the render
  // is the photograph blurred by the reads between its samples (28.7 dB; the photograph itself
  // resized up bilinearly and back, 30.3 dB), where a pixel's misplacement scores 5 dB less.
  run = testing::Lfcam(fmt::format("render {} --as-camera 3,1 --size {}x{} --out {} --quiet", file,
                                   2 * kWidth, 2 * kHeight, out));
  ASSERT_EQ(run.status, 0) << run.output;
  const cv::Mat twice = cv::imread(out);
  ASSERT_EQ(twice.size(), cv::Size(2 * kWidth, 2 * kHeight));
  cv::Mat halved;
  cv::resize(twice, halved, cv::Size(kWidth, kHeight), 0, 0, cv::INTER_AREA);
  const cv::Mat photo31 = cv::imread((dir / grid.view(3, 1).file).string());
  EXPECT_GT(cv::PSNR(halved, photo31), 27.0);
  cv::Mat shifted;  // the same, a pixel off: what a misplaced frame would score
  cv::warpAffine(photo31, shifted, cv::Mat_<double>({2, 3}, {1, 0, 1, 0, 1, 0}), photo31.size(),
                 cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  std::printf("as-camera at twice its size, brought back: %.2f dB; a pixel off: %.2f dB\n",
              cv::PSNR(halved, photo31), cv::PSNR(halved, shifted));
  EXPECT_GT(cv::PSNR(halved, photo31), cv::PSNR(halved, shifted) + 3.0);
  for (const auto& [flags, status, what] :
       {std::tuple{"--as-camera 3,1 --focal-length 50", 2,
                   "--focal-length does not go with --as-camera"},
        {"--as-camera 3", 2, "--as-camera"},
        {"--as-camera 5,0", 2, "lies outside the 5x5 grid"}}) {
    run = testing::Lfcam(fmt::format("render {} {} --out {} --quiet", file, flags, out));
    EXPECT_EQ(run.status, status) << flags << ": " << run.output;
    EXPECT_NE(run.output.find(what), std::string::npos) << flags << ": " << run.output;
  }
  const std::string simulated = (outputs / "sim.lf").string();
  ASSERT_EQ(
      testing::Lfcam("simulate lightfield --grid 2x2 --st-res 16x16 --quiet --out " + simulated)
          .status,
      0);
  run = testing::Lfcam(fmt::format("render {} --as-camera 0,0 --out {} --quiet", simulated, out));
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("records no camera for its views"), std::string::npos) << run.output;

  // A missing view, allowed, is the mean of its nearest neighbours, recorded; its camera is the
  // rig's camera at its grid position.
  fs::remove(dir / grid.view(2, 2).file);
  const ImportedGrid holed = ScanGridFolder(dir, true);
  EXPECT_EQ(holed.missing, std::vector<std::string>{"camera (2, 2)"});
  RectifiedImportReport report;
  const LightField filled = ImportRectifiedViews(dir, holed, geo, {}, &report);
  EXPECT_EQ(report.filled,
            std::vector<std::string>{"camera (2, 2) from (1, 2), (2, 1), (2, 3), (3, 2)"});
  EXPECT_LT(
      (filled.measured_poses()[2 * kN + 2].center - lf.measured_poses()[2 * kN + 2].center).norm(),
      1e-9);
  EXPECT_NEAR(filled.measured_poses()[2 * kN + 2].intrinsics->cx,
              lf.measured_poses()[2 * kN + 2].intrinsics->cx, 1e-9);
  fs::remove_all(dir);
  fs::remove_all(outputs);
}

// A rig named by indices alone has no scale: where infinity lies is assumed, and the depth
// range the sweep finds must then be the same in the views' pixels whatever was assumed (the
// range once kept a margin of two of its coarse planes, which lie closer together when the
// bracket swept is narrower: `hci-antinous` came out 0.6 to 0.8 px wider each way with infinity 16
// px behind the zero-disparity plane, as a parameters.cfg can put it, than with the 8 px assumed
// without one, and scored BadPix0.07 3.13% against 2.94%).
TEST(RectifiedImport, TheDepthRangeFoundIsTheSameInPixelsWhateverUnitsWereAssumed) {
  TrueRig rig;
  const fs::path dir = WriteRectifiedRig("lfcam_rectified_range_", &rig);
  const ImportedGrid grid = ScanGridFolder(dir, false);
  // The centre view's true disparities.
  const SimulatedModule& ref = rig.modules[std::size_t(2 * kN + 2)];
  double true_near = -1e9, true_far = 1e9;
  for (int y = 0; y < kHeight; y += 3)
    for (int x = 0; x < kWidth; x += 3) {
      const Vec3 ray = ref.world_from_camera.rotation * *ref.intrinsics.Unproject(Vec2(x, y));
      const double t = rig.scene.FirstHitDistance({ref.world_from_camera.translation, ray});
      if (!std::isfinite(t)) continue;
      const double depth = -rig.scene.rig.array.n_ca.dot(t * ray);
      const double d = kFocalPx * kPitchMm * (1 / depth - 1 / kZeroDisparityMm);
      true_near = std::max(true_near, d), true_far = std::min(true_far, d);
    }
  ASSERT_GT(true_near - true_far, 4.0);
  std::vector<std::pair<double, double>> found;  // near, far: px of disparity
  for (const double infinity_px : {20.0, 60.0}) {
    ImportOptions options;
    options.pitch_mm = 1.0;
    options.focal_px = kFocalPx;
    options.st_distance_mm = kFocalPx / infinity_px;
    const RectifiedGeometry geo = ResolveRectifiedGeometry(grid, options);
    const LightField lf = ImportRectifiedViews(dir, grid, geo);
    const DepthRange range = EstimateDepthRange(lf, 2, 2, {});
    found.emplace_back(geo.DisparityOfDepth(range.near_mm), geo.DisparityOfDepth(range.far_mm));
    SCOPED_TRACE(fmt::format("infinity {} px behind: {:.2f} .. {:.2f} px, true {:.2f} .. {:.2f}",
                             infinity_px, found.back().first, found.back().second, true_near,
                             true_far));
    EXPECT_GE(found.back().first, true_near - 0.1);
    EXPECT_LE(found.back().second, true_far + 0.1);
  }
  // The same to within half a coarse plane (a plane is 1.4 px here): the coarse sweep's planes
  // lie where the bracket puts them. (The margin of two planes of whatever spacing the bracket
  // gave made the two ranges differ by 0.55 px at the near end and 1.8 px at the far end. With
  // the simulator's rays drawn within each pixel's strata, not on a grid, the near ends found
  // differ by 0.59 px: which samples choose the nearest planes moves with the views' noise.)
  EXPECT_NEAR(found[0].first, found[1].first, 0.7);
  EXPECT_NEAR(found[0].second, found[1].second, 0.7);
  fs::remove_all(dir);
}

// A distance given (or published) that puts infinity nearer, in disparity, than the parallax the
// views show is said: nothing could lie farther behind the zero-disparity plane than infinity, so
// if the scene does, the distance is too large (on a zoomed Stanford-named gantry given one that
// put infinity 8 px behind while its world lay 15 px behind, the occlusions read the rig as
// turned and none of its map was right). Not said where the distance was assumed (it is then put
// behind the parallax), nor where the parallax fits.
TEST(RectifiedImport, ADistanceThatPutsInfinityWithinTheViewsParallaxIsSaid) {
  TrueRig rig;
  const fs::path dir = WriteRectifiedRig("lfcam_rectified_infinity_", &rig);
  const ImportedGrid grid = ScanGridFolder(dir, false);
  const auto said = [&](std::optional<double> distance, double parallax) {
    ImportOptions options;
    options.focal_px = kFocalPx;
    options.st_distance_mm = distance;
    options.scene_parallax_px = parallax;
    options.infinity_disparity_px = SceneBracketPx(parallax);
    const RectifiedGeometry geo = ResolveRectifiedGeometry(grid, options);
    for (const std::string& note : geo.notes)
      if (note.find("the distance is too large") != std::string::npos) return note;
    return std::string();
  };
  // Unit pitch: infinity lies f / Z0 px behind the zero-disparity plane.
  const std::string note = said(kFocalPx / 8.0, 15.0);
  EXPECT_NE(note.find("up to 15.0 px"), std::string::npos) << note;
  EXPECT_NE(note.find("infinity lies 8.0 px behind"), std::string::npos) << note;
  EXPECT_EQ(said(kFocalPx / 8.0, 5.0), "");
  EXPECT_EQ(said(std::nullopt, 15.0), "");
  fs::remove_all(dir);
}

TEST(RectifiedImport, ADescriptionGivesTheMetricGeometryOrThePrincipalPoints) {
  TrueRig rig;
  const fs::path dir = WriteRectifiedRig("lfcam_rectified_described_", &rig);
  nlohmann::json views = nlohmann::json::array();
  for (const SimulatedModule& m : rig.modules)
    views.push_back({{"row", m.row},
                     {"col", m.col},
                     {"file", fmt::format("scene_{:02d}_{:02d}.png", kN - m.row, m.col + 1)},
                     {"principal_point", {m.intrinsics.cx, m.intrinsics.cy}}});
  nlohmann::json description = {
      {"format", "lfcam-views"}, {"version", 2},         {"rows", kN},    {"cols", kN},
      {"pitch_mm", kPitchMm},    {"focal_px", kFocalPx}, {"views", views}};
  std::ofstream(dir / kViewsDescriptionName) << description.dump();
  // Each view's principal point: the zero-disparity plane follows from how they move.
  ImportedGrid grid = ScanGridFolder(dir, false);
  EXPECT_EQ(grid.rig, RigModel::kRectified);
  RectifiedGeometry geo = ResolveRectifiedGeometry(grid, {});
  EXPECT_TRUE(geo.assumed.empty());
  EXPECT_NEAR(geo.zero_disparity_mm, kZeroDisparityMm, 1e-6);
  LightField lf = ImportRectifiedViews(dir, grid, geo);
  // The cameras are where they were, and the st-plane is the board's plane.
  const Vec3 centre = lf.camera_center(3, 1);
  EXPECT_NEAR(centre.x(), (1 - 2) * kPitchMm, 1e-9);
  EXPECT_NEAR(centre.y(), (3 - 2) * kPitchMm, 1e-9);
  EXPECT_NEAR(lf.slab().separation_mm(), kZeroDisparityMm, 1e-9);
  EXPECT_NEAR(lf.measured_poses()[3 * kN + 1].intrinsics->cx, rig.modules[3 * kN + 1].intrinsics.cx,
              1e-9);

  // Principal points that do not fit one plane are refused, naming the view.
  views[7]["principal_point"][0] = rig.modules[7].intrinsics.cx + 0.5;
  description["views"] = views;
  std::ofstream(dir / kViewsDescriptionName) << description.dump();
  try {
    ResolveRectifiedGeometry(ScanGridFolder(dir, false), {});
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("camera (1, 2)"), std::string::npos) << e.what();
  }
  // The zero-disparity plane stated instead, in a version 1 description: refused as too old.
  description.erase("views");
  description["pattern"] = "scene_{row}_{col}.png";
  description["zero_disparity_distance_mm"] = kZeroDisparityMm;
  description["version"] = 1;
  std::ofstream(dir / kViewsDescriptionName) << description.dump();
  EXPECT_THROW(ScanGridFolder(dir, true), Error);
  fs::remove_all(dir);
}

// The same rig with its names turned half a turn (row 1 named at the bottom, column 1 at the
// right): every view's parallax agrees with that reading too, near and far exchanged. The
// occlusions tell it (depth/occlusion_order.h): `import` takes it turned back and says so, and
// the light field is the one the rig's own names give, sample for sample; --keep-axes keeps the
// names and still says what the occlusions found.
TEST(RectifiedImport, ARigNamedHalfATurnRoundIsTurnedBackByItsOcclusions) {
  TrueRig rig;
  const fs::path dir = WriteRectifiedRig("lfcam_rectified_turned_", &rig);
  const fs::path turned = dir.string() + "_turned";
  fs::remove_all(turned);
  fs::create_directories(turned);
  for (int rr = 1; rr <= kN; ++rr)
    for (int cc = 1; cc <= kN; ++cc)
      fs::copy_file(dir / fmt::format("scene_{:02d}_{:02d}.png", rr, cc),
                    turned / fmt::format("scene_{:02d}_{:02d}.png", kN + 1 - rr, kN + 1 - cc));
  const std::string named = dir.string() + ".lf", as_turned = turned.string() + ".lf",
                    kept = turned.string() + "_kept.lf";
  auto run = testing::Lfcam(fmt::format("import {} --out {}", dir.string(), named));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("near and far as named"), std::string::npos) << run.output;
  run = testing::Lfcam(fmt::format("import {} --out {}", turned.string(), as_turned));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("note: near and far exchanged as named"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("so the rig is taken turned half a turn"), std::string::npos)
      << run.output;
  const LightField a = ReadLightField(named), b = ReadLightField(as_turned);
  ASSERT_EQ(a.dims(), b.dims());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.total_bytes()), 0);
  EXPECT_LT((a.slab().uv.p_ca - b.slab().uv.p_ca).norm(), 1e-9);
  // --json records it; --keep-axes reports it and keeps the names.
  run = testing::Lfcam(fmt::format("import {} --out {} --keep-axes --json", turned.string(), kept));
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["occlusions"]["verdict"], "reversed");
  EXPECT_EQ(j["occlusions"]["turned"], false);
  EXPECT_EQ(j["axes"]["flip_rows"], false);
  const LightField c = ReadLightField(kept);
  EXPECT_NE(std::memcmp(a.data(), c.data(), a.total_bytes()), 0);
  for (const std::string& f : {named, as_turned, kept}) fs::remove(f);
  fs::remove_all(dir);
  fs::remove_all(turned);
}

TEST(RectifiedImport, FoldersThatParseSeveralWaysOrNoneAreRefusedWithTheReason) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_rectified_names_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const cv::Mat grey(8, 8, CV_8UC3, cv::Scalar(90, 90, 90));
  // Stanford names whose positions are whole numbers also parse as indices.
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c)
      cv::imwrite((dir / fmt::format("v_{:02d}_{:02d}_{}_{}.png", r, c, 10 + r, 20 + c)).string(),
                  grey);
  auto refused = [&](const std::string& what, std::optional<GridNaming> naming = {}) {
    try {
      ScanGridFolder(dir, false, naming);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused("parse several ways: stanford (2x2 views), unit-grid (2x2 views); say which with");
  EXPECT_EQ(ScanGridFolder(dir, false, GridNaming::kStanford).naming, GridNaming::kStanford);
  refused("hci: no view is named that way", GridNaming::kHci);
  cv::imwrite((dir / "notes.png").string(), grey);
  refused("unit-grid: notes.png does not parse");
  fs::remove_all(dir);
}

// A PFM (the benchmark's disparity maps): rows bottom-up, little-endian for a negative scale.
cv::Mat ReadPfm(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int w = 0, h = 0;
  double scale = 0;
  in >> magic >> w >> h >> scale;
  in.get();
  cv::Mat m(h, w, CV_32F);
  for (int y = h - 1; y >= 0; --y) in.read(reinterpret_cast<char*>(m.ptr<float>(y)), w * 4);
  return magic == "Pf" && scale < 0 && in ? m : cv::Mat();
}

// The simulator's `paper` scene through a rows x cols rectified gantry (`simulate lightfield`
// with `sim_flags`), its views in `dir`/stanford named the Stanford archive's way
// (out_RR_CC_Y_X_.png: rows counted from the top, Y = -y, X = x, no focal length or distance),
// its true depth in `dir`/truth. Returns the central view's focal length in px.
double WriteStanfordGantry(const fs::path& dir, int rows, const std::string& sim_flags,
                           int cols = 0) {
  if (cols == 0) cols = rows;
  fs::remove_all(dir);
  fs::create_directories(dir / "stanford");
  auto run = testing::Lfcam(
      fmt::format("simulate lightfield --grid {}x{} {} --depth-out {} --out {} --quiet", rows, cols,
                  sim_flags, (dir / "truth").string(), (dir / "sim.lf").string()));
  EXPECT_EQ(run.status, 0) << run.output;
  run = testing::Lfcam(fmt::format("export {} --format png-views --out {} --quiet",
                                   (dir / "sim.lf").string(), (dir / "views").string()));
  EXPECT_EQ(run.status, 0) << run.output;
  std::ifstream cameras_file(dir / "views" / "cameras.json");
  const nlohmann::json cameras = nlohmann::json::parse(cameras_file);
  double fx = 0;
  for (const auto& v : cameras["views"]) {
    const double x = v["center_mm"][0], y = v["center_mm"][1];
    if (v["row"] == rows / 2 && v["col"] == cols / 2) fx = v["fx"];
    fs::copy_file(dir / "views" / v["file"].get<std::string>(),
                  dir / "stanford" /
                      fmt::format("out_{:02d}_{:02d}_{:.6f}_{:.6f}_.png",
                                  rows - 1 - v["row"].get<int>(), v["col"].get<int>(), -y, x));
  }
  return fx;
}

// `dir`/stanford (WriteStanfordGantry's, cameras 28 mm apart, zero disparity at the board 3.6 m
// away, central view's focal length `fx`) imported with `import_flags` and its central view's
// disparity estimated: the share of its samples (every second, 15 from the edges) within 0.5
// px of the true disparity between neighbours; `largest_true` gets the truth's largest |d|.
double ShareWithinHalfPx(const fs::path& dir, double fx, const std::string& import_flags,
                         double* largest_true) {
  const std::string sim = (dir / "sim.lf").string(), truth = (dir / "truth").string();
  const LightField simulated = ReadLightField(sim);
  const DepthMap true_depth =
      ReadDepthSet(truth, simulated).at(simulated.dims().rows / 2, simulated.dims().cols / 2);
  const int w = true_depth.n_s(), h = true_depth.n_t();
  const std::string lf = (dir / "imported.lf").string(), pfm = (dir / "d.pfm").string();
  auto r = testing::Lfcam(
      fmt::format("import {} --out {} {}", (dir / "stanford").string(), lf, import_flags));
  EXPECT_EQ(r.status, 0) << r.output;
  r = testing::Lfcam(fmt::format("depth {} --out {} --disparity-pfm {} --quiet", lf,
                                 (dir / "d.png").string(), pfm));
  EXPECT_EQ(r.status, 0) << r.output;
  const cv::Mat estimate = ReadPfm(pfm);
  EXPECT_EQ(estimate.cols, w);
  int good = 0, counted = 0;
  for (int y = 15; y < h - 15; y += 2)
    for (int x = 15; x < w - 15; x += 2) {
      const double d = true_depth.depth.at<float>(h - 1 - y, x);
      const double disparity = fx * 28.0 * (1 / d - 1 / 3600.0);
      *largest_true = std::max(*largest_true, std::abs(disparity));
      ++counted;
      good += std::abs(estimate.at<float>(y, x) - disparity) < 0.5;
    }
  return double(good) / counted;
}

// A rig whose scene lies farther from zero disparity than the 8 px a step behind which infinity
// is assumed to lie (the `paper` scene through a 3 x 3 gantry zoomed in twice: the world beyond
// its board lies more than 8 px behind it), named the Stanford way with no focal length or
// distance. With infinity put 8 px behind the zero-disparity plane, the sweep could not reach
// what lies beyond it, nor nearer than 8 px in front; infinity is now put twice the largest
// parallax the views show behind it, and the estimate finds the simulator's true disparity.
TEST(RectifiedImport, AStanfordRigWithLargeParallaxGetsItsTrueDisparity) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_rectified_parallax_" + std::to_string(::getpid()));
  const double fx = WriteStanfordGantry(dir, 3, "--st-res 512x472 --st-domain 0.25,0.25,0.75,0.75");
  ASSERT_GT(fx, 0);
  double largest = 0;
  const double share = ShareWithinHalfPx(dir, fx, "--quiet", &largest);
  EXPECT_GT(largest, 8.5);  // the scene reaches past the fixed assumption's 8 px (behind)
  EXPECT_GT(share, 0.9);
  // The fixed assumption (zero disparity where infinity lies 8 px behind: 512 x 28 / 8 units).
  const double fixed = ShareWithinHalfPx(dir, fx, "--st-distance 1792 --quiet", &largest);
  EXPECT_LT(fixed, share - 0.1);
  std::printf("within 0.5 px of the true disparity: %.1f%% (the fixed assumption: %.1f%%)\n",
              100 * share, 100 * fixed);
  fs::remove_all(dir);
}

// The same through a single row of 7 cameras (a 1-D light field, as many data sets publish):
// there is no second axis to check the names against, but the parallax along the row is
// measured all the same, and infinity put behind by twice it. Before, a single row was not
// measured and took the fixed 8 px: 35.6% of the central view within 0.5 px, against 93.7%.
TEST(RectifiedImport, ASingleRowWithLargeParallaxGetsItsTrueDisparity) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_rectified_row_" + std::to_string(::getpid()));
  const double fx =
      WriteStanfordGantry(dir, 1, "--st-res 512x472 --st-domain 0.25,0.25,0.75,0.75", 7);
  ASSERT_GT(fx, 0);
  double largest = 0;
  const double share = ShareWithinHalfPx(dir, fx, "--quiet", &largest);
  EXPECT_GT(largest, 8.5);
  EXPECT_GT(share, 0.9);
  const double fixed = ShareWithinHalfPx(dir, fx, "--st-distance 1792 --quiet", &largest);
  EXPECT_LT(fixed, share - 0.1);
  // The import says what it measured along the row.
  const auto r =
      testing::Lfcam(fmt::format("import {} --out {} --json --quiet", (dir / "stanford").string(),
                                 (dir / "imported.lf").string()));
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json axes = nlohmann::json::parse(r.output)["axes"];
  EXPECT_EQ(axes["verdict"], "undecided");
  EXPECT_GT(axes["largest_px_per_step"].get<double>(), 0.8 * largest);
  EXPECT_LT(axes["largest_px_per_step"].get<double>(), 1.2 * largest);
  EXPECT_NE(axes["said"].get<std::string>().find("a single row"), std::string::npos);
  std::printf("a row: within 0.5 px of the true disparity: %.1f%% (the fixed assumption: %.1f%%)\n",
              100 * share, 100 * fixed);
  fs::remove_all(dir);
}

// A rig of small parallax (the `paper` scene through a 9 x 9 gantry 7 mm apart: up to 1.3 px
// between neighbours, the parallax of the Stanford archive's views at 256 px), named the Stanford
// way. Infinity assumed 16 px behind the zero-disparity plane (what `bench/heldout.py`'s kept half
// of such a rig 3.5 mm apart had, with the 8 px a step that the import assumed before it measured
// the parallax) lets the depth sweep reach the false depths where the scene's repeating textures
// (the board's squares, the lines of text) match again: the central view's range then spans nine
// times the scene's, and the maps of `depth --all` (reach 1) take false depths in streaks. Put
// twice the views' parallax behind, the range holds the scene and little more. The same holds
// wherever a published distance puts infinity (a metric parameters.cfg: 16-40 px behind a
// benchmark scene's +-2 px): the import records where its views show the scene, and the sweep
// brackets that; a file without the record (older imports) sweeps as far as infinity.
TEST(RectifiedImport, AStanfordRigWithSmallParallaxSweepsNoFartherThanItsScene) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_rectified_small_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  constexpr int kRows = 9;
  constexpr double kPitch = 7.0;
  nlohmann::json centres;
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kRows; ++c)
      centres["cameras"].push_back(
          {{"row", r},
           {"col", c},
           {"center", {300 + kPitch * (c - 4), 275 + kPitch * (r - 4), 3600.0}}});
  const fs::path centres_file = dir.parent_path() / (dir.filename().string() + "_centres.json");
  std::ofstream(centres_file) << centres.dump();
  const double fx = WriteStanfordGantry(
      dir, kRows, fmt::format("--st-res 256x236 --centers-from {}", centres_file.string()));
  fs::remove(centres_file);
  ASSERT_GT(fx, 0);
  // The scene's true disparities between neighbours, the central view's.
  const DepthMap true_depth =
      ReadDepthSet((dir / "truth").string(), ReadLightField((dir / "sim.lf").string())).at(4, 4);
  double true_near = -1e9, true_far = 1e9;
  for (int y = 0; y < true_depth.n_t(); ++y)
    for (int x = 0; x < true_depth.n_s(); ++x) {
      const double disparity = fx * kPitch * (1 / true_depth.depth.at<float>(y, x) - 1 / 3600.0);
      true_near = std::max(true_near, disparity), true_far = std::min(true_far, disparity);
    }
  EXPECT_LT(true_near - true_far, 2.5);
  // The range the central view's sweep takes, in px of disparity between neighbours.
  // `record`: null leaves the import's record of the scene's disparities as it is; an array
  // replaces it, anything else takes it out (as an import before the record was written).
  const auto swept = [&](const std::string& import_flags, const nlohmann::json& record = {}) {
    const std::string lf = (dir / "imported.lf").string();
    auto r = testing::Lfcam(fmt::format("import {} --out {} --json --quiet {}",
                                        (dir / "stanford").string(), lf, import_flags));
    EXPECT_EQ(r.status, 0) << r.output;
    const nlohmann::json imported = nlohmann::json::parse(r.output);
    const double f = imported["focal_px"], z0 = imported["zero_disparity_distance_mm"];
    if (!record.is_null()) {
      LightField copy = ReadLightField(lf);
      EXPECT_TRUE(copy.metadata()["import"].contains("scene_disparity_px"));
      if (record.is_array())
        copy.metadata()["import"]["scene_disparity_px"] = record;
      else
        copy.metadata()["import"].erase("scene_disparity_px");
      WriteLightField(copy, lf);
    }
    r = testing::Lfcam(
        fmt::format("depth {} --out {} --json --quiet", lf, (dir / "d.png").string()));
    EXPECT_EQ(r.status, 0) << r.output;
    const nlohmann::json range = nlohmann::json::parse(r.output)["map"]["range_mm"];
    const auto disparity = [&](double z) { return f * kPitch * (1 / z - 1 / z0); };
    return std::pair{disparity(range[0].get<double>()), disparity(range[1].get<double>())};
  };
  const auto [near, far] = swept("");
  EXPECT_GT(near, true_near);
  EXPECT_LT(far, true_far);
  EXPECT_LT(near - far, 2.2 * (true_near - true_far));  // 8 px assumed: 2.5 times
  // Infinity 16 px behind (256 px x 7 mm / 16 = 112 units): the same bracket.
  const auto [far_near, far_far] = swept("--st-distance 112");
  EXPECT_LT(far_near - far_far, 2.2 * (true_near - true_far));
  // Without the record, the sweep reaches as far as infinity and finds false depths there.
  const auto [wide_near, wide_far] = swept("--st-distance 112", "erase");
  EXPECT_GT(wide_near - wide_far, 4 * (true_near - true_far));
  // A record narrower than the scene (a surface the tracked points missed): the depths found
  // reach its end, and the whole bracket is swept after all.
  const auto [short_near, short_far] = swept("--st-distance 112", nlohmann::json{-0.3, 0.3});
  EXPECT_GT(short_near, true_near);
  EXPECT_LT(short_far, true_far);
  std::printf(
      "the scene %.2f .. %.2f px; swept %.2f .. %.2f px (infinity 16 px behind: %.2f .. %.2f; "
      "without the record %.2f .. %.2f; with one of +-0.3 px %.2f .. %.2f)\n",
      true_near, true_far, near, far, far_near, far_far, wide_near, wide_far, short_near,
      short_far);
  fs::remove_all(dir);
}

TEST(RectifiedImport, TheHciSceneLinesUpWithItsTrueDisparity) {
  const fs::path hci = fs::path(LFCAM_SOURCE_DIR) / "../shared/data/hci-antinous";
  if (!fs::is_directory(hci)) GTEST_SKIP() << hci << " is not here (../shared/data)";
  const ImportedGrid grid = ScanGridFolder(hci, false);
  EXPECT_EQ(grid.naming, GridNaming::kHci);
  ASSERT_EQ(grid.rows, 9);
  EXPECT_EQ(grid.view(8, 0).file, "input_Cam000.png");  // the top left
  EXPECT_EQ(grid.view(4, 4).file, "input_Cam040.png");
  const RectifiedGeometry geo = ResolveRectifiedGeometry(grid, {});
  const LightField lf = ImportRectifiedViews(hci, grid, geo);
  const cv::Mat truth = ReadPfm(hci / "gt_disp_lowres.pfm");
  ASSERT_EQ(truth.cols, 512);
  // Each centre-view pixel, warped by its true disparity through the imported geometry into
  // the corner views, lands on the same texture: the colour there matches far better than
  // where disparity 0 (or the opposite sign) would put it.
  std::vector<cv::Mat> views;
  for (const auto& [r, c] : {std::pair{0, 0}, {0, 8}, {8, 0}, {8, 8}, {4, 4}})
    views.push_back(ReadImageLinear(hci / grid.view(r, c).file));
  auto error_with = [&](double sign) {
    double sum = 0;
    int n = 0;
    for (int y = 20; y < 492; y += 3)
      for (int x = 20; x < 492; x += 3) {
        const double d = sign * truth.at<float>(y, x);
        const cv::Vec3f centre = views[4].at<cv::Vec3f>(y, x);
        int i = 0;
        for (const auto& [r, c] : {std::pair{0, 0}, {0, 8}, {8, 0}, {8, 8}}) {
          const Vec2 q = WarpByDisparity(lf, geo, 4, 4, Vec2(x, y), d, r, c);
          cv::Mat patch;
          cv::getRectSubPix(views[std::size_t(i++)], {1, 1},
                            cv::Point2f(float(q.x()), float(q.y())), patch);
          sum += cv::norm(patch.at<cv::Vec3f>(0, 0) - centre, cv::NORM_L1);
          ++n;
        }
      }
    return sum / n;
  };
  const double right = error_with(1), flat = error_with(0), mirrored = error_with(-1);
  EXPECT_LT(right, 0.03) << "flat " << flat << ", mirrored " << mirrored;
  EXPECT_LT(2.5 * right, flat);
  EXPECT_LT(2.5 * right, mirrored);
}

TEST(RectifiedImport, RealRectifiedViewsComeBackAsTheirPhotographs) {
  const fs::path data = fs::path(LFCAM_SOURCE_DIR) / "../shared/data";
  if (!fs::is_directory(data / "lytro-2067")) GTEST_SKIP() << data << " is not here";
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_rectified_real_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const auto& [set, photo, at] : {std::tuple{"lytro-2067", "2067_09_01.png", "0,0"},
                                       {"hci-antinous", "input_Cam016.png", "7,7"},
                                       {"lytro-2067", "2067_03_07.png", "6,6"}}) {
    const std::string lf = (dir / (std::string(set) + ".lf")).string();
    if (!fs::exists(lf)) {
      const auto run = testing::Lfcam("import " + (data / set).string() + " --out " + lf);
      ASSERT_EQ(run.status, 0) << run.output;
      EXPECT_NE(run.output.find("assumed: "), std::string::npos) << run.output;
      // No scale is known: the lengths printed say they are units of the cameras' spacing.
      EXPECT_NE(run.output.find("pitch 1 units"), std::string::npos) << run.output;
      EXPECT_NE(run.output.find(" units from the cameras"), std::string::npos) << run.output;
    }
    const std::string out = (dir / "as.png").string();
    const auto run =
        testing::Lfcam(fmt::format("render {} --as-camera {} --out {} --quiet", lf, at, out));
    ASSERT_EQ(run.status, 0) << run.output;
    const cv::Mat a = cv::imread(out), b = cv::imread((data / set / photo).string());
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0) << set << " " << photo;
  }
  // With the cameras' spacing given, the lengths are millimetres, and say so.
  const auto metric = testing::Lfcam("import " + (data / "lytro-2067").string() + " --out " +
                                     (dir / "metric.lf").string() + " --pitch-mm 0.2 --quiet");
  ASSERT_EQ(metric.status, 0) << metric.output;
  EXPECT_NE(metric.output.find("pitch 0.2 mm"), std::string::npos) << metric.output;
  EXPECT_NE(metric.output.find(" mm from the cameras"), std::string::npos) << metric.output;
  // Exported as PNG views, the imported views are the input files, pixel for pixel.
  const auto run = testing::Lfcam("export " + (dir / "lytro-2067.lf").string() +
                                  " --format png-views --out " + (dir / "views").string());
  ASSERT_EQ(run.status, 0) << run.output;
  for (int r = 0; r < 9; r += 2)
    for (int c = 0; c < 9; c += 3) {
      const cv::Mat a =
          cv::imread((dir / fmt::format("views/views/view_{:02d}_{:02d}.png", r, c)).string());
      const cv::Mat b = cv::imread(
          (data / "lytro-2067" / fmt::format("2067_{:02d}_{:02d}.png", 9 - r, c + 1)).string());
      ASSERT_FALSE(a.empty());
      EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0) << r << "," << c;
    }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam::rectified_import_test
