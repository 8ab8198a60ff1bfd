// Disparity in the benchmarks' convention: the law on a rig whose geometry is known, the PFM read
// back by another reader (OpenCV's), the HCI scene's true disparity through its imported
// geometry and the benchmark's own depth formula, and bench/hci_score.py's metrics.
#include "lfcam/depth/disparity_map.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/error.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/io/rectified_import.h"

namespace lfcam::disparity_map_test {
namespace {

namespace fs = std::filesystem;

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("lfcam_disparity_{}", ::getpid());
  fs::create_directories(dir);
  return dir / name;
}

// bench/hci_score.py run by `python` on `estimate` against `truth` (bottom-up rows, as
// WriteDisparityPfm takes them), written to scratch PFMs named `name`_*.pfm, with `flags`.
auto RunScoringScript(const std::string& python, const std::string& name, const cv::Mat& estimate,
                      const cv::Mat& truth, const std::string& flags) {
  const fs::path t = Scratch(name + "_truth.pfm"), e = Scratch(name + "_estimate.pfm");
  WriteDisparityPfm(t, truth);
  WriteDisparityPfm(e, estimate);
  const std::string script = (fs::path(LFCAM_SOURCE_DIR) / "bench/hci_score.py").string();
  return testing::RunOnce(python + " " + script + " " + e.string() + " " + t.string() + " " +
                          flags + " 2>&1");
}

// A 3 x 3 array 10 mm apart, 2000 mm in front of an st-plane sampled 2 mm apart.
LightField Rig() {
  Slab slab;
  slab.uv.rows = slab.uv.cols = 3;
  slab.uv.pitch_mm = 10;
  slab.uv.p_ca = Vec3(49, 33, 2000);
  slab.st.width_mm = 128;
  slab.st.height_mm = 96;
  return LightField({3, 3, 64, 48}, SampleType::kSrgb8, slab);
}

TEST(DisparityMap, FollowsTheBenchmarksLawAndReadsBackAsAPfm) {
  const LightField lf = Rig();
  DepthMap map;
  map.row = map.col = 1;
  map.depth.create(48, 64, CV_32FC1);
  for (int l = 0; l < 48; ++l)
    for (int k = 0; k < 64; ++k) map.depth.at<float>(l, k) = float(1500 + 10 * k + 3 * l);
  map.depth.at<float>(5, 7) = NAN;
  const cv::Mat d = DisparityOf(lf, map);
  for (int l = 0; l < 48; l += 7)
    for (int k = 0; k < 64; k += 9) {
      if (l == 5 && k == 7) continue;
      const double z = 1500 + 10 * k + 3 * l;
      EXPECT_NEAR(d.at<float>(l, k), 10.0 / 2.0 * (2000.0 / z - 1.0), 1e-5) << k << "," << l;
    }
  EXPECT_GT(d.at<float>(0, 0), 0);  // nearer than the st-plane: positive
  EXPECT_TRUE(std::isnan(d.at<float>(5, 7)));

  const fs::path pfm = Scratch("law.pfm");
  EXPECT_EQ(WriteDisparityPfm(pfm, d), 1);  // the unknown sample, written as 0
  std::ifstream in(pfm, std::ios::binary);
  std::string header(14, '\0');
  in.read(header.data(), 14);
  EXPECT_EQ(header, "Pf\n64 48\n-1.0\n");
  // OpenCV's reader gives the image upright: its top row is the highest st row.
  const cv::Mat back = cv::imread(pfm.string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(back.type(), CV_32FC1);
  ASSERT_EQ(back.size(), cv::Size(64, 48));
  for (int l = 0; l < 48; l += 5)
    for (int k = 0; k < 64; k += 5)
      if (!(l == 5 && k == 7)) {
        EXPECT_EQ(back.at<float>(47 - l, k), d.at<float>(l, k));
      }
  EXPECT_EQ(back.at<float>(42, 7), 0.0f);
  EXPECT_THROW(WriteDisparityPfm(Scratch("none.pfm"), cv::Mat()), Error);
  fs::remove_all(pfm.parent_path());
}

// The HCI scene's true disparity, turned into depth by the benchmark's own formula with the
// geometry the import assumed (f 512 px, baseline 1 unit, focus 64 units), comes back as itself.
TEST(DisparityMap, TheHciSceneGivesBackItsTrueDisparity) {
  const fs::path hci = fs::path(LFCAM_SOURCE_DIR) / "../shared/data/hci-antinous";
  if (!fs::is_directory(hci)) GTEST_SKIP() << hci << " is not here (../shared/data)";
  const ImportedGrid grid = ScanGridFolder(hci, false);
  const RectifiedGeometry geo = ResolveRectifiedGeometry(grid, {});
  const LightField lf = ImportRectifiedViews(hci, grid, geo);
  const cv::Mat truth = cv::imread((hci / "gt_disp_lowres.pfm").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(truth.size(), cv::Size(512, 512));
  const double f = 512, b = 1, focus = 64;  // as the import says it assumed
  DepthMap map;
  map.row = map.col = 4;
  map.depth.create(512, 512, CV_32FC1);
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) {
      const double d = truth.at<float>(y, x);
      map.depth.at<float>(511 - y, x) = float(b * f * focus / (d * focus + b * f));
    }
  const cv::Mat d = DisparityOf(lf, map);
  double worst = 0;
  for (int y = 0; y < 512; y += 3)
    for (int x = 0; x < 512; x += 3)
      worst = std::max(worst, double(std::abs(d.at<float>(511 - y, x) - truth.at<float>(y, x))));
  EXPECT_LT(worst, 1e-3);
}

// bench/hci_score.py against errors whose metrics are known.
TEST(DisparityMap, TheScoringScriptCountsAsTheBenchmarkDoes) {
  const std::string python = testing::PythonWith("numpy");
  if (python.empty())
    GTEST_SKIP() << "python3 with numpy is not here (scripts/install-deps.sh installs it)";
  cv::Mat truth(100, 120, CV_32FC1), estimate;
  cv::randu(truth, -2.0, 2.0);
  estimate = truth.clone();
  // Inside the 15-pixel border (90 x 70 = 6300 pixels): 315 off by 0.05, 315 off by 0.1; the
  // border's pixels, all off by 5, do not count.
  int n = 0;
  for (int y = 15; y < 85; ++y)
    for (int x = 15; x < 105; ++x, ++n)
      estimate.at<float>(y, x) += n % 20 == 0 ? 0.1f : n % 10 == 0 ? 0.05f : 0.0f;
  for (int x = 0; x < 120; ++x) estimate.at<float>(0, x) += 5.0f;
  // WriteDisparityPfm takes bottom-up rows: flip the upright images.
  cv::Mat up_truth, up_estimate;
  cv::flip(truth, up_truth, 0);
  cv::flip(estimate, up_estimate, 0);
  const fs::path t = Scratch("truth.pfm"), e = Scratch("estimate.pfm");
  WriteDisparityPfm(t, up_truth);
  WriteDisparityPfm(e, up_estimate);
  const std::string script = (fs::path(LFCAM_SOURCE_DIR) / "bench/hci_score.py").string();
  auto run = testing::RunOnce(python + " " + script + " " + e.string() + " " + t.string() +
                              " --json 2>&1");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["pixels"], 6300);
  EXPECT_NEAR(j["badpix_0.07"].get<double>(), 5.0, 1e-9);
  EXPECT_NEAR(j["badpix_0.03"].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(j["badpix_0.01"].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(j["mse_x100"].get<double>(), 100.0 * (315 * 0.01 + 315 * 0.0025) / 6300, 1e-6);
  // Maps of different sizes, or a file that is not a PFM: refused with the reason.
  WriteDisparityPfm(e, up_estimate(cv::Rect(0, 0, 100, 100)).clone());
  run = testing::RunOnce(python + " " + script + " " + e.string() + " " + t.string() + " 2>&1");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("differ in size"), std::string::npos) << run.output;
  std::ofstream(e) << "P6\n1 1\n255\nabc";
  run = testing::RunOnce(python + " " + script + " " + e.string() + " " + t.string() + " 2>&1");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("not a PFM"), std::string::npos) << run.output;
  fs::remove_all(t.parent_path());
}

// --silhouettes: a near block (rows 40-59, columns 50-79, 1 px nearer than the wall) with a ledge
// halfway between along its left side (column 49: nearer than the wall, farther than the block,
// so on the near side of one edge and the far side of another; it counts as near), whose left
// column the estimate puts on the wall (thinned) and whose right neighbours it puts on the block
// (fattened), and one pixel elsewhere half a pixel off.
TEST(DisparityMap, TheScoringScriptSaysOnWhichSideOfTheSilhouettesTheErrorLies) {
  const std::string python = testing::PythonWith("numpy");
  if (python.empty())
    GTEST_SKIP() << "python3 with numpy is not here (scripts/install-deps.sh installs it)";
  cv::Mat truth(100, 120, CV_32FC1, cv::Scalar(0.5f));
  truth(cv::Rect(50, 40, 30, 20)) = 1.5f;
  truth(cv::Rect(49, 40, 1, 20)) = 1.0f;
  cv::Mat estimate = truth.clone();
  estimate(cv::Rect(50, 40, 1, 20)) = 0.5f;
  estimate(cv::Rect(80, 40, 1, 20)) = 1.5f;
  estimate.at<float>(20, 20) += 0.5f;
  auto run = RunScoringScript(python, "block", estimate, truth, "--silhouettes --json");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  const auto& s = j["silhouettes"];
  // Near: the block's outermost ring (2 x 20 + 2 x 30 - 4) and the ledge (20). Far: the ring
  // around the block (22 x 32 - 20 x 30) less the ledge, and the column left of the ledge (22).
  EXPECT_EQ(s["near_side"]["pixels"], 116);
  EXPECT_EQ(s["far_side"]["pixels"], 106);
  EXPECT_EQ(s["elsewhere"]["pixels"], 6300 - 116 - 106);
  EXPECT_EQ(s["near_side"]["big"], 20);
  EXPECT_EQ(s["near_side"]["thinned"], 20);
  EXPECT_EQ(s["far_side"]["big"], 20);
  EXPECT_EQ(s["far_side"]["fattened"], 20);
  EXPECT_EQ(s["elsewhere"]["big"], 1);
  EXPECT_NEAR(s["near_side"]["mse_x100"].get<double>(), 100.0 * 20 / 6300, 1e-6);
  EXPECT_NEAR(s["far_side"]["mse_x100"].get<double>(), 100.0 * 20 / 6300, 1e-6);
  EXPECT_NEAR(s["elsewhere"]["mse_x100"].get<double>(), 100.0 * 0.25 / 6300, 1e-6);
  EXPECT_NEAR(j["mse_x100"].get<double>(), 100.0 * 40.25 / 6300, 1e-6);
  // The text says the same.
  run = RunScoringScript(python, "block", estimate, truth, "--silhouettes");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("116 pixels, MSEx100 0.317, 20 big errors (20 thinned"),
            std::string::npos)
      << run.output;
  // It scores an estimate: not with --registration-cost.
  const std::string script = (fs::path(LFCAM_SOURCE_DIR) / "bench/hci_score.py").string();
  const fs::path t = Scratch("block_truth.pfm");
  run = testing::RunOnce(python + " " + script + " --registration-cost " + t.string() +
                         " --silhouettes 2>&1");
  EXPECT_NE(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("not with --registration-cost"), std::string::npos) << run.output;
  fs::remove_all(t.parent_path());
}

// --bands: a wall (0.5 px) and, from column 60 on, a nearer surface (1.5 px). Inside the border
// (columns 15-104, 70 rows): the edge's columns 59 and 60; the near side 1-3 px from it, columns
// 61-63, 0.1 px too far, and 4-9 px, columns 64-69, 0.08 px too far; the far side 1-3 px,
// columns 56-58, 0.2 px too near, and 4-9 px, columns 50-55, right; and 50 pixels off by 1 px
// among the 70 columns farther from the edge.
TEST(DisparityMap, TheScoringScriptSaysWhereTheBadPixelsLie) {
  const std::string python = testing::PythonWith("numpy");
  if (python.empty())
    GTEST_SKIP() << "python3 with numpy is not here (scripts/install-deps.sh installs it)";
  cv::Mat truth(100, 120, CV_32FC1, cv::Scalar(0.5f));
  truth(cv::Rect(60, 0, 60, 100)) = 1.5f;
  cv::Mat estimate = truth.clone();
  estimate(cv::Rect(61, 0, 3, 100)) -= 0.1f;
  estimate(cv::Rect(64, 0, 6, 100)) -= 0.08f;
  estimate(cv::Rect(56, 0, 3, 100)) += 0.2f;
  estimate(cv::Rect(20, 40, 5, 10)) += 1.0f;
  estimate.row(0) += 5.0f;  // in the border: not counted
  auto run = RunScoringScript(python, "bands", estimate, truth, "--bands --json");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto b = nlohmann::json::parse(run.output)["bands"];
  EXPECT_EQ(b["bad"], 890);
  const struct {
    const char* key;
    int pixels, bad;
    double median;
  } expected[] = {{"edge", 140, 0, 0.0},         {"near_1_3", 210, 210, -0.1},
                  {"near_4_9", 420, 420, -0.08}, {"far_1_3", 210, 210, 0.2},
                  {"far_4_9", 420, 0, 0.0},      {"beyond", 4900, 50, 0.0}};
  for (const auto& e : expected) {
    EXPECT_EQ(b[e.key]["pixels"], e.pixels) << e.key;
    EXPECT_EQ(b[e.key]["bad"], e.bad) << e.key;
    EXPECT_NEAR(b[e.key]["median_error"].get<double>(), e.median, 1e-6) << e.key;
  }
  // The text says the same.
  run = RunScoringScript(python, "bands", estimate, truth, "--bands");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("where BadPix0.07's 890 pixels lie"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("210 bad (23.6% of them), median error -0.1000"), std::string::npos)
      << run.output;
}

// --picture: the truth, the estimate and the error side by side (the photograph first with
// --view), read back by OpenCV here. The estimate is the truth but for a block 0.5 px off inside
// the border and a row 5 px off in it.
TEST(DisparityMap, TheScoringScriptDrawsTheTruthTheEstimateAndTheError) {
  const std::string python = testing::PythonWith("cv2, numpy");
  if (python.empty())
    GTEST_SKIP() << "python3 with numpy and OpenCV is not here (scripts/install-deps.sh installs "
                    "them)";
  cv::Mat truth(100, 120, CV_32FC1);
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 120; ++x) truth.at<float>(y, x) = float(-2.0 + 4.0 * x / 119.0);
  cv::Mat estimate = truth.clone();
  estimate(cv::Rect(40, 30, 20, 10)) += 0.5f;
  estimate.row(98) += 5.0f;  // upright row 1, in the border
  const fs::path out = Scratch("picture.png"), view = Scratch("view.png");
  auto run = RunScoringScript(python, "picture", estimate, truth, "--picture " + out.string());
  ASSERT_EQ(run.status, 0) << run.output;
  const cv::Mat p = cv::imread(out.string(), cv::IMREAD_COLOR);
  ASSERT_EQ(p.size(), cv::Size(3 * 120 + 2 * 8, 100));
  // The truth and the estimate in the same colours where they agree; the gaps white.
  EXPECT_EQ(p.at<cv::Vec3b>(80, 10), p.at<cv::Vec3b>(80, 128 + 10));
  EXPECT_NE(p.at<cv::Vec3b>(80, 10), p.at<cv::Vec3b>(80, 110));
  EXPECT_EQ(p.at<cv::Vec3b>(50, 123), cv::Vec3b(255, 255, 255));
  // The error: black where they agree, white 0.3 px off or more inside the border, dimmed in it
  // (the rows upright: the block at upright rows 60-69, the border's row at 1).
  const int e0 = 2 * 128;
  EXPECT_EQ(p.at<cv::Vec3b>(50, e0 + 20), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(p.at<cv::Vec3b>(65, e0 + 50), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(p.at<cv::Vec3b>(1, e0 + 50), cv::Vec3b(85, 85, 85));
  // With the photograph first; one of another size is refused, naming both sizes.
  cv::imwrite(view.string(), cv::Mat(100, 120, CV_8UC3, cv::Scalar(10, 20, 30)));
  run = RunScoringScript(python, "picture", estimate, truth,
                         "--picture " + out.string() + " --view " + view.string());
  ASSERT_EQ(run.status, 0) << run.output;
  const cv::Mat four = cv::imread(out.string(), cv::IMREAD_COLOR);
  ASSERT_EQ(four.size(), cv::Size(4 * 120 + 3 * 8, 100));
  EXPECT_EQ(four.at<cv::Vec3b>(50, 60), cv::Vec3b(10, 20, 30));
  cv::imwrite(view.string(), cv::Mat(90, 120, CV_8UC3, cv::Scalar::all(0)));
  run = RunScoringScript(python, "picture", estimate, truth,
                         "--picture " + out.string() + " --view " + view.string());
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("120x90, the maps are 120x100"), std::string::npos) << run.output;
  // A flat truth (one depth) is drawn too, without a word from NumPy.
  run =
      RunScoringScript(python, "flat", cv::Mat(100, 120, CV_32FC1, cv::Scalar(0.5f)),
                       cv::Mat(100, 120, CV_32FC1, cv::Scalar(0.5f)), "--picture " + out.string());
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(run.output.find("Warning"), std::string::npos) << run.output;
  run = RunScoringScript(python, "picture", estimate, truth, "--view " + view.string());
  EXPECT_NE(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("give --picture too"), std::string::npos) << run.output;
  fs::remove_all(out.parent_path());
}

// --registration-cost: the truth moved one row and one column against itself. A vertical step of
// 1 px (columns 60 and on) costs nothing moved down a row and one column of 70 pixels (of the 90 x
// 70 inside the border) moved right.
TEST(DisparityMap, TheScoringScriptSaysWhatOneSampleOfRegistrationCosts) {
  const std::string python = testing::PythonWith("numpy");
  if (python.empty())
    GTEST_SKIP() << "python3 with numpy is not here (scripts/install-deps.sh installs it)";
  cv::Mat truth(100, 120, CV_32FC1, cv::Scalar(0.5f));
  truth(cv::Rect(60, 0, 60, 100)) = 1.5f;
  const fs::path t = Scratch("step.pfm");
  WriteDisparityPfm(t, truth);
  const std::string script = (fs::path(LFCAM_SOURCE_DIR) / "bench/hci_score.py").string();
  auto run = testing::RunOnce(python + " " + script + " --registration-cost " + t.string() +
                              " --json 2>&1");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["one_row"]["badpix_0.07"].get<double>(), 0.0);
  EXPECT_EQ(j["one_row"]["mse_x100"].get<double>(), 0.0);
  EXPECT_NEAR(j["one_column"]["badpix_0.07"].get<double>(), 100.0 * 70 / 6300, 1e-9);
  EXPECT_NEAR(j["one_column"]["mse_x100"].get<double>(), 100.0 * 70 / 6300, 1e-6);
  // One file is what it takes; two are refused.
  run = testing::RunOnce(python + " " + script + " --registration-cost " + t.string() + " " +
                         t.string() + " 2>&1");
  EXPECT_NE(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("expected GT.pfm"), std::string::npos) << run.output;
  fs::remove_all(t.parent_path());
}

}  // namespace
}  // namespace lfcam::disparity_map_test
