// Views that recorded black (a plenoptic camera's views beyond its main lens's aperture: the
// corners of a 15 x 15 decode) imported from a rectified rig: filled from their neighbours, said,
// recorded, and left out of the depth sweep, so that neither a wide-aperture render nor the depth
// map is darkened or misled by them. The simulator's `paper` scene through a 5 x 5 gantry, named
// NAME_RR_CC, imported whole and with three views blackened.
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/view_filling.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/io/rectified_import.h"

namespace lfcam::dark_views_test {
namespace {

namespace fs = std::filesystem;

constexpr int kRows = 5;

// The views of a simulated 5 x 5 rig in `dir`/whole as grid_RR_CC.png (row 01 at the top).
void WriteRig(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir / "whole");
  auto run = testing::Lfcam(
      fmt::format("simulate lightfield --grid {0}x{0} --st-res 192x176 --out {1} --quiet", kRows,
                  (dir / "sim.lf").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  run = testing::Lfcam(fmt::format("export {} --format png-views --out {} --quiet",
                                   (dir / "sim.lf").string(), (dir / "views").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream cameras_file(dir / "views" / "cameras.json");
  const nlohmann::json cameras = nlohmann::json::parse(cameras_file);
  for (const auto& v : cameras["views"])
    fs::copy_file(dir / "views" / v["file"].get<std::string>(),
                  dir / "whole" /
                      fmt::format("grid_{:02d}_{:02d}.png", kRows - v["row"].get<int>(),
                                  v["col"].get<int>() + 1));
}

double MeanLevel(const std::string& png) { return cv::mean(cv::imread(png))[1]; }

// Three of the rig's views black or nearly (two corners and one beside a corner), as 8-bit PNGs,
// in `dir`/dark beside `dir`/whole.
const std::vector<std::string> kBlackened = {"grid_01_01.png", "grid_01_02.png", "grid_05_05.png"};
void WriteBlackenedRig(const fs::path& dir) {
  fs::copy(dir / "whole", dir / "dark", fs::copy_options::recursive);
  for (const std::string& name : kBlackened) {
    const cv::Mat view = cv::imread((dir / "dark" / name).string());
    cv::Mat black(view.size(), CV_8UC3, cv::Scalar(2, 3, 2));
    ASSERT_TRUE(cv::imwrite((dir / "dark" / name).string(), black));
  }
}

// A tiny 3 x 3 rig of noise in `dir`, named tiny_RR_CC (row 01 at the top): its top-left view
// black, or nearly; its bottom-right one dim (a quarter of the others' brightness).
void WriteTinyRig(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  cv::RNG rng(7);
  for (int top = 1; top <= 3; ++top)
    for (int col = 1; col <= 3; ++col) {
      cv::Mat view(40, 48, CV_8UC3);
      rng.fill(view, cv::RNG::UNIFORM, 60, 200);
      if (top == 1 && col == 1) view.setTo(cv::Scalar(1, 2, 1));  // black, nearly
      if (top == 3 && col == 3) view /= 4;                        // dim
      ASSERT_TRUE(
          cv::imwrite((dir / fmt::format("tiny_{:02d}_{:02d}.png", top, col)).string(), view));
    }
}

// The green mean of view (row, col) of a light field of the tiny rig's size.
double TinyViewMean(const LightField& lf, int row, int col) {
  const cv::Mat view(40, 48, CV_8UC3, const_cast<std::uint8_t*>(lf.view_data(row, col)));
  return cv::mean(view)[1];
}

// The import itself on the tiny rig (fast enough for the sanitizers): the black view is filled
// with the mean of its nearest neighbours and recorded; the dim one is kept as it is; told to,
// the import keeps the black one too.
TEST(DarkViews, TheImportFillsABlackViewAndKeepsADimOne) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_dark_tiny_" + std::to_string(::getpid()));
  WriteTinyRig(dir);
  const ImportedGrid grid = ScanGridFolder(dir, false);
  const RectifiedGeometry geometry = ResolveRectifiedGeometry(grid, {});
  RectifiedImportReport report;
  const LightField lf = ImportRectifiedViews(dir, grid, geometry, {}, &report);
  ASSERT_EQ(report.dark.size(), 1u);
  EXPECT_EQ(report.dark[0], "tiny_01_01.png (2, 0)");  // the top-left view: lfcam's row 2
  ASSERT_EQ(report.filled.size(), 1u);
  EXPECT_EQ(FilledViews(lf), (std::vector<std::pair<int, int>>{{2, 0}}));
  EXPECT_EQ(lf.metadata()["import"]["dark_views"][0]["file"], "tiny_01_01.png");
  // Filled: as bright as its neighbours (the mean of (1, 0) and (2, 1)), not black.
  EXPECT_GT(TinyViewMean(lf, 2, 0), 0.8 * std::min(TinyViewMean(lf, 1, 0), TinyViewMean(lf, 2, 1)));
  // The dim view is a photograph, kept sample for sample.
  const cv::Mat dim = cv::imread((dir / "tiny_03_03.png").string());
  EXPECT_NEAR(TinyViewMean(lf, 0, 2), cv::mean(dim)[1], 1e-9);
  // Told to keep them, nothing is filled.
  RectifiedImportReport kept;
  ImportRectifiedViews(dir, grid, geometry, {}, &kept, /*fill_dark_views=*/false);
  EXPECT_TRUE(kept.dark.empty());
  EXPECT_TRUE(kept.filled.empty());
  fs::remove_all(dir);
}

// The same rig imported as parallel cameras (resampled by the build, as a Blender grid is): the
// build fills the black view from its neighbours, at its own pose, says so, records it, and keeps
// the dim one; told to, it keeps the black one too. Before, a parallel rig's black view was
// built as a photograph and darkened every render that took it in.
TEST(DarkViews, AParallelRigsBlackViewIsFilledByTheBuild) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_dark_parallel_" + std::to_string(::getpid()));
  WriteTinyRig(dir / "rig");
  const std::string flags = "--rig parallel --focal-px 50 --st-distance 1000";
  auto run = testing::Lfcam(fmt::format("import {} {} --out {} --json --quiet",
                                        (dir / "rig").string(), flags, (dir / "p.lf").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json imported = nlohmann::json::parse(run.output);
  ASSERT_EQ(imported["dark"].size(), 1u) << imported;
  EXPECT_EQ(imported["dark"][0], "tiny_01_01.png (2, 0)");
  const LightField lf = ReadLightField((dir / "p.lf").string());
  EXPECT_EQ(FilledViews(lf), (std::vector<std::pair<int, int>>{{2, 0}}));
  EXPECT_EQ(lf.metadata()["dark_views"].size(), 1u);
  EXPECT_GT(TinyViewMean(lf, 2, 0), 0.8 * std::min(TinyViewMean(lf, 1, 0), TinyViewMean(lf, 2, 1)));
  EXPECT_LT(TinyViewMean(lf, 0, 2), 0.5 * TinyViewMean(lf, 1, 1));  // the dim one, kept
  // Said in the output; kept when told to.
  run = testing::Lfcam(
      fmt::format("import {} {} --out {}", (dir / "rig").string(), flags, (dir / "p.lf").string()));
  EXPECT_NE(run.output.find("1 view black or nearly"), std::string::npos) << run.output;
  run = testing::Lfcam(fmt::format("import {} {} --keep-dark-views --out {} --json --quiet",
                                   (dir / "rig").string(), flags, (dir / "k.lf").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(nlohmann::json::parse(run.output)["dark"].empty());
  EXPECT_LT(TinyViewMean(ReadLightField((dir / "k.lf").string()), 2, 0), 5);
  fs::remove_all(dir);
}

TEST(DarkViews, BlackViewsAreFilledFromTheirNeighboursSaidAndLeftOutOfDepth) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_dark_views_" + std::to_string(::getpid()));
  WriteRig(dir);
  WriteBlackenedRig(dir);
  const auto import = [&](const std::string& folder) {
    const auto r =
        testing::Lfcam(fmt::format("import {} --out {} --json --quiet", (dir / folder).string(),
                                   (dir / (folder + ".lf")).string()));
    EXPECT_EQ(r.status, 0) << r.output;
    return nlohmann::json::parse(r.output);
  };
  EXPECT_TRUE(import("whole")["dark"].empty());
  const nlohmann::json imported = import("dark");
  ASSERT_EQ(imported["dark"].size(), 3u) << imported["dark"];
  ASSERT_EQ(imported["filled"].size(), 3u);
  for (const std::string& name : kBlackened)
    EXPECT_NE(imported["dark"].dump().find(name), std::string::npos) << imported["dark"];
  // Said, and recorded in the file where depth finds them (grid_01_01: lfcam's row 4, column 0).
  auto said = testing::Lfcam(
      fmt::format("import {} --out {}", (dir / "dark").string(), (dir / "dark.lf").string()));
  ASSERT_EQ(said.status, 0) << said.output;
  EXPECT_NE(said.output.find("3 views black or nearly"), std::string::npos) << said.output;
  const LightField lf = ReadLightField((dir / "dark.lf").string());
  const auto filled = FilledViews(lf);
  EXPECT_EQ(filled.size(), 3u);
  EXPECT_NE(std::find(filled.begin(), filled.end(), std::pair{kRows - 1, 0}), filled.end());
  EXPECT_EQ(lf.metadata()["import"]["dark_views"].size(), 3u);
  const auto info = testing::Lfcam("info " + (dir / "dark.lf").string());
  EXPECT_NE(info.output.find("3 views filled from their neighbours"), std::string::npos)
      << info.output;
  // Told to, the import keeps them as they are.
  const auto kept =
      testing::Lfcam(fmt::format("import {} --out {} --keep-dark-views --json --quiet",
                                 (dir / "dark").string(), (dir / "kept.lf").string()));
  ASSERT_EQ(kept.status, 0) << kept.output;
  EXPECT_TRUE(nlohmann::json::parse(kept.output)["dark"].empty());
  EXPECT_TRUE(nlohmann::json::parse(kept.output)["filled"].empty());

  // A render whose aperture takes in every camera (the corners 2.8 grid steps from the centre):
  // the same brightness as the whole rig's. Unfilled, the three black views took its mean level
  // from 129.7 to 122.4.
  const auto render = [&](const std::string& name) {
    const std::string out = (dir / (name + ".png")).string();
    const auto r = testing::Lfcam(fmt::format("render {} --aperture 7 --size 96 --out {} --quiet",
                                              (dir / (name + ".lf")).string(), out));
    EXPECT_EQ(r.status, 0) << r.output;
    return out;
  };
  const double whole = MeanLevel(render("whole")), dark = MeanLevel(render("dark"));
  // A render as a filled camera says it shows a blend (grid_01_01: lfcam's camera (4, 0)).
  const auto as_filled = testing::Lfcam(fmt::format(
      "render {} --as-camera 4,0 --out {}", (dir / "dark.lf").string(), (dir / "c.png").string()));
  EXPECT_EQ(as_filled.status, 0) << as_filled.output;
  EXPECT_NE(as_filled.output.find("camera (4, 0) was not photographed"), std::string::npos)
      << as_filled.output;
  EXPECT_NEAR(dark, whole, 0.005 * whole) << "the whole rig " << whole << ", blackened " << dark;

  // The central view's disparity: the blackened rig's is the whole rig's (the filled views are
  // left out of the sweep, as the views too dark to match were before they were filled).
  const auto depth = [&](const std::string& name) {
    const std::string pfm = (dir / (name + ".pfm")).string();
    const auto r = testing::Lfcam(fmt::format("depth {} --out {} --disparity-pfm {} --json --quiet",
                                              (dir / (name + ".lf")).string(),
                                              (dir / (name + "_depth.png")).string(), pfm));
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(nlohmann::json::parse(r.output)["map"]["views_too_dark"].empty());
    return cv::imread(pfm, cv::IMREAD_UNCHANGED);  // OpenCV's PFM reader, not lfcam's
  };
  const cv::Mat whole_map = depth("whole"), dark_map = depth("dark");
  ASSERT_EQ(whole_map.size(), dark_map.size());
  ASSERT_EQ(whole_map.type(), CV_32FC1);
  cv::Mat off;
  cv::compare(cv::abs(whole_map - dark_map), 0.07, off, cv::CMP_GT);
  const double off_share = cv::countNonZero(off) / double(off.total());
  EXPECT_LT(off_share, 0.025);  // 3.1% with the filled views swept
  std::printf(
      "render's mean level: whole %.2f, blackened %.2f; disparity more than 0.07 px apart: "
      "%.2f%%\n",
      whole, dark, 100 * off_share);
  fs::remove_all(dir);
}

// Exported for other tools, a filled view is no photograph: the PNG grid keeps it, marked, and
// COLMAP and NeRF are not given it (no image, no camera, no point seen in it), each view keeping
// its id; the output says which were left out.
TEST(DarkViews, FilledViewsAreNotExportedAsPhotographs) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_dark_export_" + std::to_string(::getpid()));
  WriteRig(dir);
  WriteBlackenedRig(dir);
  const std::string lf = (dir / "dark.lf").string(), maps = (dir / "maps").string();
  auto r = testing::Lfcam(fmt::format("import {} --out {} --quiet", (dir / "dark").string(), lf));
  ASSERT_EQ(r.status, 0) << r.output;
  r = testing::Lfcam(fmt::format("depth {} --all --out {} --quiet", lf, maps));
  ASSERT_EQ(r.status, 0) << r.output;
  // Ids row * cols + col + 1 of lfcam's grid (row 0 at the bottom): grid_01_01 is (4, 0),
  // grid_01_02 (4, 1), grid_05_05 (0, 4).
  const std::set<int> filled_ids = {4 * kRows + 0 + 1, 4 * kRows + 1 + 1, 0 * kRows + 4 + 1};

  r = testing::Lfcam(
      fmt::format("export {} --format png-views --out {}", lf, (dir / "png").string()));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("wrote 25 views"), std::string::npos) << r.output;
  std::ifstream cameras_file(dir / "png" / "cameras.json");
  const nlohmann::json cameras = nlohmann::json::parse(cameras_file);
  std::set<int> marked;
  for (const auto& v : cameras["views"])
    if (v.value("filled", false))
      marked.insert(v["row"].get<int>() * kRows + v["col"].get<int>() + 1);
  EXPECT_EQ(marked, filled_ids);

  r = testing::Lfcam(fmt::format("export {} --format colmap --depth {} --out {}", lf, maps,
                                 (dir / "colmap").string()));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("wrote 22 views"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("left out 3 views"), std::string::npos) << r.output;
  std::ifstream images(dir / "colmap" / "sparse/0/images.txt");
  std::set<int> image_ids;
  int line_number = 0;
  for (std::string line; std::getline(images, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (line_number++ % 2 == 0) image_ids.insert(std::stoi(line));  // the pose line
  }
  EXPECT_EQ(image_ids.size(), 22u);
  for (const int id : filled_ids) EXPECT_EQ(image_ids.count(id), 0u) << id;
  EXPECT_FALSE(fs::exists(dir / "colmap" / "images" / "view_04_00.png"));
  std::ifstream points(dir / "colmap" / "sparse/0/points3D.txt");
  int tracked = 0;
  for (std::string line; std::getline(points, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double skip;
    for (int i = 0; i < 8; ++i) fields >> skip;  // id, X, Y, Z, R, G, B, error
    for (int image, index; fields >> image >> index;) {
      EXPECT_EQ(filled_ids.count(image), 0u) << line;
      EXPECT_EQ(image_ids.count(image), 1u) << line;
      ++tracked;
    }
  }
  EXPECT_GT(tracked, 1000);

  r = testing::Lfcam(
      fmt::format("export {} --format nerf --out {} --quiet", lf, (dir / "nerf").string()));
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream transforms_file(dir / "nerf" / "transforms.json");
  EXPECT_EQ(nlohmann::json::parse(transforms_file)["frames"].size(), 22u);
  fs::remove_all(dir);
}

// The depth lookup between cameras reads no filled view (on the CPU and in the GL shader alike):
// its blend of neighbours would put their ghosts into the render. Between two photographed and
// two filled cameras (grid rows 3-4, columns 0-1: the filled are (4, 0) and (4, 1)), the render
// is measured against the whole rig's there: 15.4 dB when the filled views were read, 29.9 dB
// now.
TEST(DarkViews, TheDepthLookupReadsNoFilledView) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_dark_lookup_" + std::to_string(::getpid()));
  WriteRig(dir);
  WriteBlackenedRig(dir);
  const auto render = [&](const std::string& name, const std::string& flags) {
    const std::string lf = (dir / (name + ".lf")).string(), out = (dir / (name + ".png")).string();
    auto r = testing::Lfcam(fmt::format("import {} --out {} --quiet", (dir / name).string(), lf));
    EXPECT_EQ(r.status, 0) << r.output;
    r = testing::Lfcam(fmt::format(
        "render {} --as-camera 3.5,0.5 --interpolation depth {} --out {} --quiet", lf, flags, out));
    return std::pair{r, out};
  };
  const auto [whole_run, whole] = render("whole", "");
  ASSERT_EQ(whole_run.status, 0) << whole_run.output;
  const auto [dark_run, dark] = render("dark", "");
  ASSERT_EQ(dark_run.status, 0) << dark_run.output;
  const double psnr = cv::PSNR(cv::imread(dark), cv::imread(whole));
  EXPECT_GT(psnr, 27.0);
  std::printf("between two filled and two photographed cameras: %.2f dB of the whole rig's\n",
              psnr);
  const auto [gl_run, gl] = render("dark", "--backend gl");
  if (gl_run.status == 1 && gl_run.output.find("--backend gl: no OpenGL") != std::string::npos) {
    std::printf("the GL renderer not checked: %s\n", gl_run.output.c_str());
  } else {
    ASSERT_EQ(gl_run.status, 0) << gl_run.output;
    EXPECT_GT(cv::PSNR(cv::imread(gl), cv::imread(dark)), 50.0);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam::dark_views_test
