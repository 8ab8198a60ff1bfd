// The HCI benchmark's parameters.cfg: what lfcam reads of it, its disparity-depth law, and bad
// files refused naming the line and the key; a benchmark folder with one imports metrically.
#include "lfcam/io/hci_parameters.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/test_support.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/io/rectified_import.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

constexpr const char* kParameters = R"([intrinsics]
focal_length_mm = 100
image_resolution_x_px = 64
image_resolution_y_px = 48
sensor_size_mm = 35
fstop = 100

[extrinsics]
num_cams_x = 3
num_cams_y = 3
baseline_mm = 90.0
focus_distance_m = 4.25
center_cam_rx_rad = 1.5707963

; a comment
[meta]
disp_min = -2.0
disp_max = 1.5
scene = example
)";

TEST(HciParameters, ReadsTheRigAndItsDisparityLaw) {
  const HciParameters p = ParseHciParameters(kParameters, "parameters.cfg");
  EXPECT_EQ(p.width_px, 64);
  EXPECT_EQ(p.cams_y, 3);
  EXPECT_TRUE(p.metric());
  EXPECT_DOUBLE_EQ(*p.focal_px(), 100.0 * 64 / 35);
  EXPECT_DOUBLE_EQ(*p.focus_distance_mm, 4250.0);
  EXPECT_EQ(*p.disp_min, -2.0);
  EXPECT_EQ(p.values.at("meta.scene"), "example");
  // Zero disparity at the focus distance; the law and its inverse agree.
  EXPECT_NEAR(p.DepthOfDisparity(0), 4250.0, 1e-9);
  for (const double d : {-1.5, 0.3, 2.0})
    EXPECT_NEAR(p.DisparityOfDepth(p.DepthOfDisparity(d)), d, 1e-12);
  EXPECT_LT(p.DepthOfDisparity(1.0), 4250.0);  // positive disparity is nearer
}

// As the benchmark's own files are written (every key of its scenes', Windows line ends), and
// saved again by an editor that marks UTF-8 with a byte order mark.
TEST(HciParameters, ReadsTheBenchmarksOwnFilesWithWindowsLineEndsAndAByteOrderMark) {
  std::string text;
  for (const char* line :
       {"[intrinsics]",
        "focal_length_mm = 100",
        "image_resolution_x_px = 512",
        "image_resolution_y_px = 512",
        "sensor_size_mm = 35",
        "fstop = 100",
        "",
        "[extrinsics]",
        "num_cams_x = 9",
        "num_cams_y = 9",
        "baseline_mm = 50.0",
        "focus_distance_m = 4.25",
        "center_cam_x_m = 0.0",
        "center_cam_y_m = -4.5",
        "center_cam_z_m = 0.8",
        "center_cam_rx_rad = 1.5707963",
        "center_cam_ry_rad = 0.0",
        "center_cam_rz_rad = 0.0",
        "offset = 0",
        "",
        "[meta]",
        "disp_min = -2.0",
        "disp_max = 2.3",
        "frustum_disp_min = -2.5",
        "frustum_disp_max = 2.5",
        "depth_map_scale = 100.0",
        "scene = antinous",
        "category = additional",
        "date = 12/08/2016",
        "version = v1.0",
        "authors = Katrin Honauer, Ole Johannsen, Daniel Kondermann, Bastian Goldluecke",
        "contact = contact@lightfield-analysis.net",
        "cc = CC BY-NC-SA 4.0"})
    text += std::string(line) + "\r\n";
  for (const std::string& file : {text, "\xEF\xBB\xBF" + text}) {
    const HciParameters p = ParseHciParameters(file, "parameters.cfg");
    EXPECT_EQ(p.width_px, 512);
    EXPECT_EQ(p.cams_x, 9);
    EXPECT_DOUBLE_EQ(*p.focus_distance_mm, 4250.0);
    EXPECT_EQ(*p.disp_max, 2.3);
    EXPECT_EQ(p.values.at("meta.authors"),
              "Katrin Honauer, Ole Johannsen, Daniel Kondermann, Bastian Goldluecke");
  }
}

TEST(HciParameters, BadFilesAreRefusedNamingTheLineAndTheKey) {
  auto refused = [](const std::string& text, const std::string& what) {
    try {
      ParseHciParameters(text, "p.cfg");
      ADD_FAILURE() << "accepted: " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  const std::string good = kParameters;
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  refused(replaced("baseline_mm = 90.0", ""),
          "line 12: extrinsics.focus_distance_m given without extrinsics.baseline_mm");
  refused(replaced("sensor_size_mm = 35", ""),
          "p.cfg: intrinsics.focal_length_mm intrinsics.image_resolution_x_px "
          "intrinsics.image_resolution_y_px given without intrinsics.sensor_size_mm");
  refused(replaced("num_cams_y = 3", ""),
          "p.cfg: extrinsics.num_cams_x given without extrinsics.num_cams_y");
  refused(replaced("baseline_mm = 90.0", "baseline_mm = ninety"),
          "line 11: extrinsics.baseline_mm = 'ninety' is not a number");
  refused(replaced("baseline_mm = 90.0", "baseline_mm = -90"),
          "line 11: extrinsics.baseline_mm = -90 must be positive");
  refused(replaced("num_cams_x = 3", "num_cams_x = 2.5"), "must be a whole number");
  refused(replaced("fstop = 100", "fstop"), "line 6: expected 'key = value'");
  refused(replaced("[meta]", "[meta"), "a section header must read [name]");
  refused(good + "[extrinsics]\nbaseline_mm = 1\n", "extrinsics.baseline_mm is given twice");
}

// A benchmark folder of `views` views of 64 x 48 (input_Cam000.png ...) with `parameters` as its
// parameters.cfg, in a scratch directory of the running test.
fs::path HciFolder(const char* parameters, int views) {
  const fs::path dir = testing::MakeScratchDir("lfcam_hci");
  std::ofstream(dir / kHciParametersName) << parameters;
  for (int i = 0; i < views; ++i)
    cv::imwrite((dir / fmt::format("input_Cam{:03d}.png", i)).string(),
                cv::Mat(48, 64, CV_8UC3, cv::Scalar(10 * i, 20, 30)));
  return dir;
}

TEST(HciParameters, ABenchmarkFolderWithItImportsMetrically) {
  const fs::path dir = HciFolder(kParameters, 9);
  cv::imwrite((dir / "valid_mask.png").string(), cv::Mat(48, 64, CV_8UC1, cv::Scalar(255)));
  const ImportedGrid grid = ScanGridFolder(dir, false);
  EXPECT_EQ(grid.naming, GridNaming::kHci);
  EXPECT_EQ(grid.ignored, std::vector<std::string>{"valid_mask.png"});
  EXPECT_EQ(grid.view(2, 0).file, "input_Cam000.png");  // the top left
  EXPECT_EQ(grid.view(0, 2).file, "input_Cam008.png");
  const RectifiedGeometry geo = ResolveRectifiedGeometry(grid, {});
  EXPECT_TRUE(geo.assumed.empty());
  EXPECT_DOUBLE_EQ(geo.focal_px, 100.0 * 64 / 35);
  EXPECT_DOUBLE_EQ(geo.zero_disparity_mm, 4250.0);
  EXPECT_DOUBLE_EQ(geo.pitch_mm, 90.0);
  // The camera to the right of the centre: 90 mm along x, its principal point moved by f b / Z0.
  EXPECT_NEAR(grid.view(1, 2).x_mm - grid.view(1, 1).x_mm, 90.0, 1e-12);
  EXPECT_NEAR(geo.PrincipalPoint(90, 0).x() - geo.PrincipalPoint(0, 0).x(),
              geo.focal_px * 90 / 4250, 1e-9);
  // Where the depth sweep looks for the scene: the file's disparity range (-2 .. 1.5) widened by
  // half its span, joined to twice the parallax the views show (a whole px), whatever the units.
  ASSERT_TRUE(geo.scene_disparity_px.has_value());
  EXPECT_DOUBLE_EQ((*geo.scene_disparity_px)[0], -3.75);
  EXPECT_DOUBLE_EQ((*geo.scene_disparity_px)[1], 3.25);
  ImportOptions tracked;
  tracked.scene_parallax_px = 2.2;
  const RectifiedGeometry wider = ResolveRectifiedGeometry(grid, tracked);
  EXPECT_DOUBLE_EQ((*wider.scene_disparity_px)[0], -5.0);
  EXPECT_DOUBLE_EQ((*wider.scene_disparity_px)[1], 5.0);
  EXPECT_EQ(ImportRectifiedViews(dir, grid, wider).metadata()["import"]["scene_disparity_px"],
            nlohmann::json::array({-5.0, 5.0}));
}

// A copy whose views were resized since keeps the sensor: the focal length scales with them, and
// the import says so; views of another aspect ratio are not a resize, and are refused.
TEST(HciParameters, ViewsOfAnotherSizeScaleTheFocalLengthOrAreRefused) {
  const fs::path dir = HciFolder(kParameters, 9);
  for (int i = 0; i < 9; ++i)  // half the size parameters.cfg gives (64 x 48)
    cv::imwrite((dir / fmt::format("input_Cam{:03d}.png", i)).string(),
                cv::Mat(24, 32, CV_8UC3, cv::Scalar(10 * i, 20, 30)));
  const RectifiedGeometry geo = ResolveRectifiedGeometry(ScanGridFolder(dir, false), {});
  EXPECT_DOUBLE_EQ(geo.focal_px, 100.0 * 32 / 35);
  EXPECT_TRUE(geo.assumed.empty());
  ASSERT_EQ(geo.notes.size(), 1u);
  EXPECT_NE(geo.notes[0].find("64x48, but they are 32x24"), std::string::npos) << geo.notes[0];
  // The same disparities as at full size, in the views' own pixels: f b / Z0 halves.
  EXPECT_NEAR(geo.PrincipalPoint(90, 0).x() - geo.PrincipalPoint(0, 0).x(),
              0.5 * 100.0 * 64 / 35 * 90 / 4250, 1e-9);
  for (int i = 0; i < 9; ++i)  // another aspect ratio
    cv::imwrite((dir / fmt::format("input_Cam{:03d}.png", i)).string(),
                cv::Mat(48, 48, CV_8UC3, cv::Scalar(10 * i, 20, 30)));
  const std::string refused =
      testing::ErrorOf([&] { ResolveRectifiedGeometry(ScanGridFolder(dir, false), {}); });
  EXPECT_NE(refused.find("64x48, but they are 48x48"), std::string::npos) << refused;
  // A focal length given on the command line stands, whatever the file says.
  ImportOptions o;
  o.focal_px = 50.0;
  EXPECT_DOUBLE_EQ(ResolveRectifiedGeometry(ScanGridFolder(dir, false), o).focal_px, 50.0);
}

// Folders made elsewhere in the benchmark's format often give only the grid, the image size and
// the disparity range: they import in disparity units, every unit assumed and said.
constexpr const char* kPartialParameters = R"([intrinsics]
image_resolution_x_px = 64
image_resolution_y_px = 48

[extrinsics]
num_cams_x = 3
num_cams_y = 2

[meta]
disp_min = -1.2
disp_max = 2.5
)";

TEST(HciParameters, APartialFileGivesWhatItHasAndTheImportAssumesTheRest) {
  const HciParameters p = ParseHciParameters(kPartialParameters, "parameters.cfg");
  EXPECT_FALSE(p.metric());
  EXPECT_FALSE(p.focal_px().has_value());
  EXPECT_FALSE(p.baseline_mm.has_value());
  EXPECT_EQ(p.cams_x, 3);
  EXPECT_EQ(*p.disp_max, 2.5);
  EXPECT_THROW(p.DepthOfDisparity(0.0), Error);

  // Six views: no square grid, so the shape can only come from the file.
  const fs::path dir = HciFolder(kPartialParameters, 6);
  const ImportedGrid grid = ScanGridFolder(dir, false);
  EXPECT_EQ(grid.naming, GridNaming::kHci);
  EXPECT_EQ(grid.rows, 2);
  EXPECT_EQ(grid.cols, 3);
  EXPECT_EQ(grid.view(1, 0).file, "input_Cam000.png");  // the top left
  EXPECT_FALSE(grid.positions_known);
  const RectifiedGeometry geo = ResolveRectifiedGeometry(grid, {});
  EXPECT_DOUBLE_EQ(geo.pitch_mm, 1.0);
  EXPECT_DOUBLE_EQ(geo.focal_px, 64.0);  // the larger image side
  ASSERT_EQ(geo.assumed.size(), 3u);     // the spacing, the focal length, the zero-disparity plane
  EXPECT_NE(geo.assumed[0].find("1 unit apart"), std::string::npos) << geo.assumed[0];
  // Without the file, six views are refused: they are not a square grid.
  fs::remove(dir / kHciParametersName);
  const std::string refused = testing::ErrorOf([&] { ScanGridFolder(dir, false); });
  EXPECT_NE(refused.find("not a square grid"), std::string::npos) << refused;
}

}  // namespace
}  // namespace lfcam
