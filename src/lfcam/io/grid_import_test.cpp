// Importing views named the Stanford and Blender ways against a synthetic grid whose truth is
// known (a textured plane photographed by ideal cameras at named positions), bad folders, and
// the real Blender data set in ../shared/data when it is present.
#include "lfcam/io/grid_import.h"

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lfcam/calib/lightfield_build.h"
#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_metrics.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/io/parallel_import.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

constexpr double kPlaneMm = 2000;  // the textured plane's distance from the cameras
constexpr double kFocalPx = 200;
constexpr int kWidth = 160, kHeight = 120;

// A smooth random texture on the plane z = 0, 1 mm a texel, centred on the origin.
cv::Mat PlaneTexture() {
  cv::Mat t(1600, 1600, CV_32FC3);
  cv::randu(t, 0, 255);
  cv::GaussianBlur(t, t, {0, 0}, 6);
  cv::normalize(t, t, 0, 255, cv::NORM_MINMAX);
  return t;
}

// What an ideal camera at (x, y, kPlaneMm) looking along -z sees of the plane (y up, image
// rows down).
cv::Mat ViewOfPlane(const cv::Mat& texture, double x, double y) {
  cv::Mat map_x(kHeight, kWidth, CV_32F), map_y(kHeight, kWidth, CV_32F);
  for (int v = 0; v < kHeight; ++v)
    for (int u = 0; u < kWidth; ++u) {
      const double wx = x + (u - 0.5 * (kWidth - 1)) * kPlaneMm / kFocalPx;
      const double wy = y - (v - 0.5 * (kHeight - 1)) * kPlaneMm / kFocalPx;
      map_x.at<float>(v, u) = float(wx + 800);
      map_y.at<float>(v, u) = float(800 - wy);  // texture rows run down, y up
    }
  cv::Mat out, out8;
  cv::remap(texture, out, map_x, map_y, cv::INTER_LINEAR);
  out.convertTo(out8, CV_8UC3);
  return out8;
}

// The Blender exporter's names: RR counts rows down (first number -y), CC counts columns to the
// left (second number x).
fs::path WriteBlenderGrid(const std::string& name, int n, double pitch, bool blender = true) {
  const fs::path dir = fs::temp_directory_path() / (name + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const cv::Mat texture = PlaneTexture();
  for (int rr = 0; rr < n; ++rr)
    for (int cc = 0; cc < n; ++cc) {
      const double y = ((n - 1) / 2.0 - rr) * pitch, x = ((n - 1) / 2.0 - cc) * pitch;
      const std::string file = blender
                                   ? fmt::format("Cam_{:02d}_{:02d}_{:f}_{:f}_{}_{}.png", rr, cc,
                                                 -y, x, kFocalPx * 36.0 / kWidth, 36)
                                   : fmt::format("out_{:02d}_{:02d}_{:f}_{:f}_.png", rr, cc, -y, x);
      cv::imwrite((dir / file).string(), ViewOfPlane(texture, x, y));
    }
  return dir;
}

double Psnr(const cv::Mat& a, const cv::Mat& b) {
  return CompareImages(a.clone(), b.clone()).psnr_db;
}

cv::Mat ViewImage(const LightField& lf, int row, int col) {
  const auto& d = lf.dims();
  cv::Mat view(d.n_t, d.n_s, CV_8UC3, const_cast<std::uint8_t*>(lf.view_data(row, col)));
  cv::Mat top_down;
  cv::flip(view, top_down, 0);  // st rows run bottom-up in the file
  cv::Mat bgr;
  cv::cvtColor(top_down, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}

TEST(GridImport, ABlenderGridOfAPlaneBecomesViewsThatAgreeOnIt) {
  const fs::path dir = WriteBlenderGrid("lfcam_import_blender_", 3, 40.0);
  const ImportedGrid grid = ScanGridFolder(dir, false);
  EXPECT_EQ(grid.naming, GridNaming::kBlender);
  ASSERT_EQ(grid.rows, 3);
  ASSERT_EQ(grid.cols, 3);
  EXPECT_NEAR(grid.pitch_mm, 40.0, 1e-6);
  // lfcam's (0, 0) is the bottom left seen from behind: the exporter's last row, last column.
  EXPECT_NE(grid.view(0, 0).file.find("Cam_02_02_"), std::string::npos) << grid.view(0, 0).file;
  EXPECT_NEAR(grid.view(0, 0).x_mm, -40.0, 1e-6);
  EXPECT_NEAR(grid.view(0, 0).y_mm, -40.0, 1e-6);

  // The st-plane's distance, estimated from the views, is the plane's.
  const ImportedSession session = MakeImportedSession(dir, grid, {});
  EXPECT_TRUE(session.st_distance_estimated);
  EXPECT_NEAR(session.focal_px, kFocalPx, 1e-9);
  EXPECT_NEAR(session.st_distance_mm, kPlaneMm, 0.03 * kPlaneMm);

  // With the st-plane on the textured plane, the reference window is what the central camera
  // sees, and built in its own window (the reference moved by the camera's offset, a whole number
  // of samples here) every view is its own camera's image, sample for sample.
  ImportOptions exact;
  exact.st_distance_mm = kPlaneMm;
  const ImportedSession s = MakeImportedSession(dir, grid, exact);
  EXPECT_EQ(s.calibration.slab.st_domain.s0, 0);
  EXPECT_EQ(s.calibration.slab.st_domain.t1, 1);
  BuildOptions b;
  b.n_s = kWidth;
  b.n_t = kHeight;
  b.view_windows = true;
  const LightField lf = BuildLightField(dir, s.manifest, s.calibration, b);
  ASSERT_TRUE(lf.has_view_windows());
  const cv::Rect inner(2, 2, kWidth - 4, kHeight - 4);  // the bilinear reads' last sample aside
  const int step = int(std::lround(40.0 * kFocalPx / kPlaneMm));  // samples between cameras
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(lf.st_offset(r, c), (StOffset{(c - 1) * step, (r - 1) * step})) << r << "," << c;
      EXPECT_GT(Psnr(ViewImage(lf, r, c)(inner),
                     cv::imread((dir / grid.view(r, c).file).string())(inner)),
                40.0)
          << r << "," << c;
    }
  // Shared windows (every view samples the central camera's window): the same picture of the
  // plane in every view.
  b.view_windows = false;
  const LightField shared = BuildLightField(dir, s.manifest, s.calibration, b);
  const cv::Rect away(12, 12, kWidth - 24, kHeight - 24);  // away from the views' edges
  const cv::Mat centre = ViewImage(shared, 1, 1);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      EXPECT_GT(Psnr(ViewImage(shared, r, c)(away), centre(away)), 35.0) << r << "," << c;
  // A mirrored convention would put the views 2 x 40 mm apart on the plane: far from agreeing.
  EXPECT_EQ(lf.camera_center(0, 2), Vec3(40, -40, kPlaneMm));
  fs::remove_all(dir);
}

// A regular grid of parallel cameras, an even count of them 3 samples apart on the plane: the
// estimated st-plane is moved to where they lie whole samples apart (and the window half a
// sample, the grid's centre lying between cameras), so every camera's pixels are st samples and
// a render as any of them, corners included, is its photograph.
TEST(GridImport, EveryParallelViewKeepsItsPixelsAtAWholeSampleDistance) {
  const fs::path dir = WriteBlenderGrid("lfcam_import_whole_", 4, 30.0);
  const ImportedGrid grid = ScanGridFolder(dir, false);
  const auto snapped = WholeSampleStDistance(grid, kFocalPx, 2100);
  ASSERT_TRUE(snapped.has_value());
  EXPECT_NEAR(snapped->first, kPlaneMm, 1e-9);  // 30 mm x 200 px / 3 samples
  EXPECT_EQ(snapped->second, 3);
  const std::string lf = (dir.string() + ".lf");
  auto run = testing::Lfcam("import " + dir.string() + " --out " + lf + " --json --quiet");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NEAR(nlohmann::json::parse(run.output)["st_distance_mm"].get<double>(), kPlaneMm, 1e-6);
  EXPECT_EQ(ReadLightFieldHeader(lf).version, 4u);  // each view in its own window
  run = testing::Lfcam("info " + lf);
  EXPECT_NE(run.output.find("view windows  each view its own"), std::string::npos) << run.output;
  run = testing::Lfcam("import " + dir.string() + " --out " + lf + ".x --st-windows some");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("--st-windows: 'some' is not shared or views"), std::string::npos)
      << run.output;
  for (const auto& [r, c] : {std::pair{0, 0}, {3, 3}, {1, 2}, {0, 3}}) {
    const std::string as = dir.string() + "_as.png";
    run = testing::Lfcam(fmt::format("render {} --as-camera {},{} --out {} --quiet", lf, r, c, as));
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_GT(Psnr(cv::imread(as), cv::imread((dir / grid.view(r, c).file).string())), 45.0)
        << r << "," << c;
    fs::remove(as);
  }
  // Cameras off a regular grid have no such distance.
  ImportedGrid irregular = grid;
  irregular.views[5].x_mm += 0.37;
  EXPECT_FALSE(WholeSampleStDistance(irregular, kFocalPx, 2100).has_value());
  fs::remove(lf);
  fs::remove_all(dir);
}

TEST(GridImport, StanfordNamesNeedTheFocalLengthAndBadFoldersAreNamed) {
  const fs::path dir = WriteBlenderGrid("lfcam_import_stanford_", 2, 30.0, false);
  const ImportedGrid grid = ScanGridFolder(dir, false);
  EXPECT_EQ(grid.naming, GridNaming::kStanford);
  EXPECT_EQ(grid.rig, RigModel::kRectified);  // the archive's views are; these are not: parallel
  try {
    MakeImportedSession(dir, grid, {});
    ADD_FAILURE() << "imported without a focal length";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--focal-px"), std::string::npos) << e.what();
  }
  ImportOptions o;
  o.focal_px = kFocalPx;
  EXPECT_NEAR(MakeImportedSession(dir, grid, o).st_distance_mm, kPlaneMm, 0.05 * kPlaneMm);

  auto refused = [&](const std::string& what) {
    try {
      ScanGridFolder(dir, false);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  // An incomplete grid (and with --allow-missing, the hole named).
  const std::string one = grid.view(1, 1).file;
  fs::rename(dir / one, dir / "held");
  refused("camera (1, 1) is missing");
  // ... placed by the files beside it, in the folder's own names, and named as it would be,
  // its positions (NAME_RR_CC_Y_X_.png) not guessed.
  std::vector<std::string> fields;
  for (std::size_t start = 0;;) {
    const auto at = one.find('_', start);
    fields.push_back(one.substr(start, at - start));
    if (at == std::string::npos) break;
    start = at + 1;
  }
  ASSERT_EQ(fields.size(), 6u) << one;
  fields[3] = fields[4] = "*";
  refused(fmt::format("camera (1, 1) would be {}: it lies in the row of {} and the column of {}",
                      fmt::format("{}", fmt::join(fields, "_")), grid.view(1, 0).file,
                      grid.view(0, 1).file));
  EXPECT_EQ(ScanGridFolder(dir, true).missing, std::vector<std::string>{"camera (1, 1)"});
  // A view of another size.
  cv::imwrite((dir / one).string(), cv::Mat(10, 10, CV_8UC3, cv::Scalar(0)));
  refused(one + ": 10x10");
  // A name that does not parse; a name of the other convention.
  fs::remove(dir / one);
  fs::rename(dir / "held", dir / one);
  cv::imwrite((dir / "notes.png").string(), cv::Mat(10, 10, CV_8UC3, cv::Scalar(0)));
  refused("stanford: notes.png does not parse");
  fs::remove(dir / "notes.png");
  fs::copy_file(dir / one, dir / "Cam_05_05_0_0_30_36.png");
  refused("names the same camera (0_0) as Cam_05_05_0_0_30_36.png");
  fs::remove(dir / "Cam_05_05_0_0_30_36.png");
  // Not an image at all.
  std::ofstream(dir / one) << "not a png";
  refused(one);
  fs::remove_all(dir);
  EXPECT_THROW(ScanGridFolder(dir, false), Error);
}

// A view missing from a folder is named as its file would be: a unit grid's (padded or not,
// tagged or not), the HCI benchmark's, a numbered sequence's; where the names carry measured
// positions (Stanford's, Blender's), its indices with a '*' for each position, which is not
// guessed.
TEST(GridImport, AMissingViewIsNamedAsItsFileWouldBe) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_import_hole_" + std::to_string(::getpid()));
  const cv::Mat grey(8, 8, CV_8UC3, cv::Scalar(90, 90, 90));
  // `name(r, c)` for every view of a 3 x 3 grid (rows from the top) but `missing`.
  const auto refused = [&](const auto& name, int missing, const std::string& what,
                           std::optional<GridShape> shape = {}) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (int i = 0; i < 9; ++i)
      if (i != missing) cv::imwrite((dir / name(i / 3, i % 3)).string(), grey);
    try {
      ScanGridFolder(dir, false, std::nullopt, shape);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  const auto plenoptic = [](int r, int c) {
    return fmt::format("2067_{:02d}_{:02d}.png", r + 1, c + 1);
  };
  refused(plenoptic, 5, "would be 2067_02_03.png: it lies in the row of 2067_02_02.png");
  refused(plenoptic, 0, "would be 2067_01_01.png");
  const auto tagged = [](int r, int c) { return fmt::format("v_r{}_c{}.png", r, c); };
  refused(tagged, 7, "would be v_r2_c1.png");
  const auto hci = [](int r, int c) { return fmt::format("input_Cam{:03d}.png", r * 3 + c); };
  refused(hci, 4, "would be input_Cam004.png", GridShape{3, 3});
  refused(hci, 4, "is missing, 8 of its 9 views here", GridShape{3, 3});
  const auto numbered = [](int r, int c) { return fmt::format("frame{:04d}.png", 7 + r * 3 + c); };
  refused(numbered, 8, "would be frame0015.png", GridShape{3, 3});
  // Positions measured by a gantry are not made up: the hole's indices, its positions '*'.
  const auto stanford = [](int r, int c) {
    return fmt::format("out_{:02d}_{:02d}_{}.5_{}.25_.png", r, c, -10 * r, 10 * c);
  };
  refused(stanford, 4,
          "camera (1, 1) would be out_01_01_*_*_.png: it lies in the row of "
          "out_01_00_-10.5_0.25_.png");
  const auto blender = [](int r, int c) {
    return fmt::format("Original Camera_{:02d}_{:02d}_{}.5_{}.25_30_36.jpg", r + 9, c + 9, 10 * r,
                       10 * c);
  };
  refused(blender, 5, "would be Original Camera_10_11_*_*_30_36.jpg: it lies in the row of");
  fs::remove_all(dir);
}

TEST(GridImport, ADescribedFolderNeedsNoNames) {
  const fs::path dir = WriteBlenderGrid("lfcam_import_described_", 2, 30.0);
  // Rename the views plainly and describe them: view_ROW_COL.png, lfcam's grid.
  const ImportedGrid named = ScanGridFolder(dir, false);
  for (const GridView& v : named.views)
    fs::rename(dir / v.file, dir / fmt::format("view_{}_{}.png", v.row, v.col));
  std::ofstream(dir / kViewsDescriptionName) << nlohmann::json{
      {"format", "lfcam-views"},
      {"version", 1},
      {"rows", 2},
      {"cols", 2},
      {"pitch_mm", 30.0},
      {"focal_px", kFocalPx},
      {"st_distance_mm", 1500},
      {"pattern", "view_{row}_{col}.png"}}.dump();
  const ImportedGrid grid = ScanGridFolder(dir, false);
  EXPECT_EQ(grid.naming, GridNaming::kDescription);
  EXPECT_EQ(grid.view(1, 0).file, "view_1_0.png");
  EXPECT_NEAR(grid.view(1, 0).x_mm, -15.0, 1e-9);
  EXPECT_NEAR(grid.view(1, 0).y_mm, 15.0, 1e-9);
  const ImportedSession s = MakeImportedSession(dir, grid, {});
  EXPECT_FALSE(s.st_distance_estimated);
  EXPECT_EQ(s.st_distance_mm, 1500);
  fs::remove_all(dir);
}

TEST(GridImport, TheShopDataSetImportsAndRenders) {
  const fs::path shop = fs::path(LFCAM_SOURCE_DIR) / "../shared/data/shop-center-9x9";
  if (!fs::is_directory(shop)) GTEST_SKIP() << shop << " is not here (../shared/data)";
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_import_shop_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string lf = (dir / "shop.lf").string();
  auto run = testing::Lfcam("import " + shop.string() + " --out " + lf + " --json --quiet");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["naming"], "blender-grid");
  EXPECT_EQ(j["rows"], 9);
  EXPECT_NEAR(j["pitch_mm"].get<double>(), 800.0 / 26, 1e-3);
  EXPECT_NEAR(j["focal_px"].get<double>(), 800.0, 1e-9);  // 30 mm of a 36 mm sensor, 960 px
  // Most of the shop lies about 8 m away (the data set's viewer focused at 8.1 m).
  EXPECT_GT(j["st_distance_mm"].get<double>(), 7000);
  EXPECT_LT(j["st_distance_mm"].get<double>(), 9500);
  // Every camera's photograph comes back as a render at that camera, the whole frame, corners
  // included (the st domain covers what every camera sees): the central camera's pixels are st
  // samples; the others' are resampled, then read again (the double interpolation per-view
  // windows will remove).
  ImportedGrid grid = ScanGridFolder(shop, false);
  for (const auto& [r, c] : {std::pair{4, 4}, {0, 0}, {8, 8}, {0, 8}}) {
    const std::string as = (dir / "as.png").string();
    run = testing::Lfcam(fmt::format("render {} --as-camera {},{} --out {} --quiet", lf, r, c, as));
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_GT(Psnr(cv::imread(as), cv::imread((shop / grid.view(r, c).file).string())), 45.0)
        << r << "," << c;
  }
  run = testing::Lfcam("render " + lf + " --size 256 --out " + (dir / "r.png").string() +
                       " --focal-length 700 --aperture 60 --integrator cameras --quiet");
  EXPECT_EQ(run.status, 0) << run.output;
  fs::remove_all(dir);
}

// Views encoded otherwise than as 8-bit colour (a plenoptic decode's 16-bit PNGs, a render with
// alpha, grey views) import as 8-bit sRGB colour, and the import says so rather than drop the
// bits, the alpha or the grey silently; 8-bit colour views get no such note. The 16-bit views
// come back as their values rounded to 8 bits.
TEST(GridImport, ViewsOfOtherEncodingsAreSaidToBeStoredAs8BitColour) {
  const fs::path root =
      fs::temp_directory_path() / ("lfcam_encodings_" + std::to_string(::getpid()));
  fs::remove_all(root);
  cv::RNG rng(11);
  cv::Mat base(24, 32, CV_8UC3);
  rng.fill(base, cv::RNG::UNIFORM, 30, 230);
  const auto write = [&](const std::string& kind) {
    fs::create_directories(root / kind);
    for (int top = 1; top <= 2; ++top)
      for (int col = 1; col <= 2; ++col) {
        cv::Mat v = base.clone(), out;
        if (kind == "sixteen") v.convertTo(out, CV_16UC3, 257.0);
        if (kind == "alpha") cv::cvtColor(v, out, cv::COLOR_BGR2BGRA);
        if (kind == "grey") cv::cvtColor(v, out, cv::COLOR_BGR2GRAY);
        if (kind == "colour") out = v;
        ASSERT_TRUE(cv::imwrite(
            (root / kind / fmt::format("v_{:02d}_{:02d}.png", top, col)).string(), out));
      }
  };
  const auto notes = [&](const std::string& kind) {
    write(kind);
    std::string all;
    for (const std::string& n : NamingNotes(ScanGridFolder(root / kind, false))) all += n + "\n";
    return all;
  };
  EXPECT_EQ(notes("colour"), "");
  EXPECT_NE(notes("sixteen").find("16 bits a channel: stored as 8"), std::string::npos);
  EXPECT_NE(notes("alpha").find("alpha channel: left out"), std::string::npos);
  const std::string grey = notes("grey");
  EXPECT_NE(grey.find("grey"), std::string::npos);
  EXPECT_EQ(grey.find("alpha"), std::string::npos);
  // Through the command: said, and the 16-bit views stored as their 8-bit values.
  const auto run = testing::Lfcam(fmt::format("import {} --out {}", (root / "sixteen").string(),
                                              (root / "sixteen.lf").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("note: the views have 16 bits a channel"), std::string::npos)
      << run.output;
  const LightField lf = ReadLightField((root / "sixteen.lf").string());
  const cv::Mat view(24, 32, CV_8UC3, const_cast<std::uint8_t*>(lf.view_data(0, 0)));
  cv::Mat expected;
  cv::cvtColor(base, expected, cv::COLOR_BGR2RGB);
  cv::flip(expected, expected, 0);  // lfcam's rows count up
  EXPECT_EQ(cv::norm(view, expected, cv::NORM_INF), 0.0);
  fs::remove_all(root);
}

// An archive unpacked as it comes: its views one or two folders down (the Stanford archive's
// rectified/). The one folder that holds them is imported, and said; several are refused, named;
// views of a kind lfcam does not read are named too.
TEST(GridImport, ViewsOneOrTwoFoldersDownAreFoundAndSaid) {
  const fs::path root = fs::temp_directory_path() / ("lfcam_nested_" + std::to_string(::getpid()));
  fs::remove_all(root);
  cv::RNG rng(5);
  const auto write_views = [&](const fs::path& dir) {
    fs::create_directories(dir);
    for (int top = 1; top <= 3; ++top)
      for (int col = 1; col <= 3; ++col) {
        cv::Mat v(24, 32, CV_8UC3);
        rng.fill(v, cv::RNG::UNIFORM, 30, 230);
        ASSERT_TRUE(cv::imwrite((dir / fmt::format("v_{:02d}_{:02d}.png", top, col)).string(), v));
      }
  };
  write_views(root / "scene" / "rectified");
  // What unpacking on a Mac leaves beside it, and a hidden folder: not views to choose from.
  write_views(root / "__MACOSX" / "scene");
  write_views(root / ".cache");
  fs::create_directories(root / "scene" / "notes");
  EXPECT_EQ(ViewsSubfolder(root), root / "scene" / "rectified");
  EXPECT_EQ(ViewsSubfolder(root / "scene"), root / "scene" / "rectified");
  EXPECT_EQ(ViewsSubfolder(root / "scene" / "rectified"), std::nullopt);  // views of its own
  EXPECT_EQ(ViewsSubfolder(root / "scene" / "notes"), std::nullopt);      // nothing under it

  const auto run = testing::Lfcam(
      fmt::format("import {} --out {}", root.string(), (root / "found.lf").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find(fmt::format("note: {} holds no views of its own: the views of {} "
                                        "imported",
                                        root.string(), (root / "scene" / "rectified").string())),
            std::string::npos)
      << run.output;
  const auto direct =
      testing::Lfcam(fmt::format("import {} --out {}", (root / "scene" / "rectified").string(),
                                 (root / "direct.lf").string()));
  ASSERT_EQ(direct.status, 0) << direct.output;
  const LightField found = ReadLightField((root / "found.lf").string());
  const LightField given = ReadLightField((root / "direct.lf").string());
  ASSERT_EQ(found.total_bytes(), given.total_bytes());
  EXPECT_EQ(std::memcmp(found.data(), given.data(), found.total_bytes()), 0);
  EXPECT_EQ(found.metadata()["import"]["notes"][0].get<std::string>().find(root.string()), 0u);

  // Two folders of views: neither is guessed; both are named.
  write_views(root / "other");
  try {
    ViewsSubfolder(root);
    ADD_FAILURE() << "two folders of views were not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2 folders in it hold views (other, scene/rectified)"),
              std::string::npos)
        << e.what();
  }
  const auto refused = testing::Lfcam(
      fmt::format("import {} --out {}", root.string(), (root / "refused.lf").string()));
  EXPECT_NE(refused.status, 0);
  EXPECT_FALSE(fs::exists(root / "refused.lf"));

  // Views of a kind lfcam does not read are named, with the remedy, not passed over in silence.
  fs::create_directories(root / "tiff");
  for (int col = 1; col <= 3; ++col)
    ASSERT_TRUE(cv::imwrite((root / "tiff" / fmt::format("v_01_{:02d}.tif", col)).string(),
                            cv::Mat(8, 8, CV_8UC3, cv::Scalar(50, 90, 130))));
  try {
    ScanGridFolder(root / "tiff", false);
    ADD_FAILURE() << "a folder of TIFF views was not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("its images are 3 .tif files, which lfcam does not "
                                         "read: convert them to PNG"),
              std::string::npos)
        << e.what();
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace lfcam
