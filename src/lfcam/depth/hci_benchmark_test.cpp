// bench/hci_benchmark.py: a copy of the HCI 4D Light Field Benchmark, laid out as downloaded, run
// as a submission (disp_maps/SCENE.pfm and runtimes/SCENE.txt, what the benchmark's evaluation
// toolkit reads) and scored, on scenes the simulator makes with their truth.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/test_support.h"
#include "lfcam/depth/disparity_map.h"
#include "lfcam/io/lightfield_export.h"
#include "lfcam/sim/depth_truth.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam::hci_benchmark_test {
namespace {

namespace fs = std::filesystem;

// The 9 x 9 rig `lf` as the benchmark lays out a scene: input_CamNNN.png, NNN = 9 x (the row
// from the top) + the column (lfcam's row 0 is the bottom one).
void WriteBenchmarkScene(const LightField& lf, const fs::path& dir) {
  fs::create_directories(dir);
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c) {
      cv::Mat bgr;
      cv::cvtColor(ViewImage(lf, r, c), bgr, cv::COLOR_RGB2BGR);
      cv::imwrite((dir / fmt::format("input_Cam{:03d}.png", 9 * (8 - r) + c)).string(), bgr);
    }
}

// BadPix(0.07) of `estimate` against `truth` over the maps less a 15-pixel border, both read by
// OpenCV's PFM reader (neither lfcam's writer nor the script's reader).
double BadPix007(const fs::path& estimate, const fs::path& truth) {
  const cv::Mat e = cv::imread(estimate.string(), cv::IMREAD_UNCHANGED);
  const cv::Mat t = cv::imread(truth.string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(e.type(), CV_32FC1);
  EXPECT_EQ(e.size(), t.size());
  int bad = 0, n = 0;
  for (int y = 15; y < t.rows - 15; ++y)
    for (int x = 15; x < t.cols - 15; ++x, ++n)
      bad += !(std::abs(e.at<float>(y, x) - t.at<float>(y, x)) <= 0.07f);
  return 100.0 * bad / n;
}

// Three scenes: one of the training kind (the `paper` scene through cameras 16 mm apart, views of
// 128 x 118 samples, disparities of -1.1 .. +0.5 px, the truth beside them), one of the test kind
// (the same views, no truth) and one whose view is cut short; and an earlier run's map of the
// broken scene already in the output.
TEST(HciBenchmarkScript, RunsEverySceneAsASubmissionAndScoresThoseWithTruth) {
  const std::string python = testing::PythonWith("numpy");
  if (python.empty())
    GTEST_SKIP() << "python3 with numpy is not here (scripts/install-deps.sh installs it)";
  Scene scene = MakePaperScene();
  scene.rig.array.pitch_mm = 16.0;
  SimulateLightFieldOptions o;
  o.rows = o.cols = 9;
  o.n_s = 128;
  o.n_t = 118;
  o.supersampling = 3;
  const LightField lf = SimulateLightField(scene, o);
  const fs::path dir = testing::MakeScratchDir("lfcam_hci_benchmark");
  const fs::path benchmark = dir / "benchmark", out = dir / "out";
  const fs::path training = benchmark / "training" / "paper";
  WriteBenchmarkScene(lf, training);
  WriteDisparityPfm(training / "gt_disp_lowres.pfm",
                    DisparityOf(lf, GroundTruthDepth(scene, lf, 4, 4).map));
  WriteBenchmarkScene(lf, benchmark / "test" / "hidden");
  const fs::path broken = benchmark / "stratified" / "broken";
  WriteBenchmarkScene(lf, broken);
  fs::resize_file(broken / "input_Cam010.png", 300);
  fs::create_directories(out / "disp_maps");
  std::ofstream(out / "disp_maps" / "broken.pfm") << "an earlier run's";

  const std::string script = (fs::path(LFCAM_SOURCE_DIR) / "bench/hci_benchmark.py").string();
  const auto run = testing::RunOnce(fmt::format("{} {} {} {} --lfcam {} --json 2>{}", python,
                                                script, benchmark.string(), out.string(),
                                                LFCAM_CLI_PATH, (dir / "stderr.txt").string()));
  std::ifstream err_file(dir / "stderr.txt");
  const std::string err((std::istreambuf_iterator<char>(err_file)), {});
  EXPECT_EQ(run.status, 1) << run.output << err;  // a scene failed
  EXPECT_NE(err.find("broken failed: lfcam import: lfcam: error:"), std::string::npos) << err;
  EXPECT_NE(err.find("input_Cam010.png"), std::string::npos) << err;
  const auto j = nlohmann::json::parse(run.output);

  // The broken scene: named with lfcam's reason, and nothing of it in the output.
  ASSERT_TRUE(j["failed"].contains("broken"));
  EXPECT_NE(j["failed"]["broken"].get<std::string>().find("input_Cam010.png"), std::string::npos);
  EXPECT_FALSE(fs::exists(out / "disp_maps" / "broken.pfm"));
  EXPECT_FALSE(fs::exists(out / "runtimes" / "broken.txt"));

  // The others: the toolkit's files, the runtime as its seconds.
  for (const char* name : {"paper", "hidden"}) {
    ASSERT_TRUE(j["scenes"].contains(name)) << run.output;
    const double seconds = j["scenes"][name]["runtime_s"];
    EXPECT_GT(seconds, 0.0);
    double written = 0;
    std::ifstream(out / "runtimes" / fmt::format("{}.txt", name)) >> written;
    EXPECT_NEAR(written, seconds, 1e-3) << name;
    const cv::Mat map = cv::imread((out / "disp_maps" / fmt::format("{}.pfm", name)).string(),
                                   cv::IMREAD_UNCHANGED);
    EXPECT_EQ(map.size(), cv::Size(128, 118)) << name;
  }
  EXPECT_FALSE(j["scenes"]["hidden"].contains("scores"));

  // The scene with truth scored as the benchmark scores it, and well.
  const auto& scores = j["scenes"]["paper"]["scores"];
  const double badpix = BadPix007(out / "disp_maps" / "paper.pfm", training / "gt_disp_lowres.pfm");
  EXPECT_NEAR(scores["badpix_0.07"].get<double>(), badpix, 1e-6);
  EXPECT_EQ(scores["pixels"], (128 - 30) * (118 - 30));
  std::cout << fmt::format(
      "[hci benchmark] simulated training scene: BadPix0.07 {:.2f}%, "
      "MSEx100 {:.3f}, {:.1f} s\n",
      badpix, scores["mse_x100"].get<double>(), j["scenes"]["paper"]["runtime_s"].get<double>());
  // Floors a little above what was measured (8.65% and 1.35; 2026-12-04): a map misplaced by the
  // script (another scene's, its rows the other way) scores tens of per cent.
  EXPECT_LE(badpix, 10.0);
  EXPECT_LE(scores["mse_x100"].get<double>(), 1.6);

  // The table, and a scene asked for that is not there. With OpenCV's Python module, the scored
  // scene drawn too: its centre view (input_Cam040.png), truth, map and error side by side.
  const std::string with_cv2 = testing::PythonWith("cv2, numpy");
  const auto table = testing::RunOnce(fmt::format(
      "{} {} {} {} --lfcam {} --scenes paper{} 2>&1", with_cv2.empty() ? python : with_cv2, script,
      benchmark.string(), out.string(), LFCAM_CLI_PATH, with_cv2.empty() ? "" : " --pictures"));
  EXPECT_EQ(table.status, 0) << table.output;
  EXPECT_NE(table.output.find(fmt::format("{:<16} {:>9.2f}%", "paper", badpix)), std::string::npos)
      << table.output;
  if (!with_cv2.empty()) {
    const cv::Mat drawn = cv::imread((out / "pictures" / "paper.jpg").string(), cv::IMREAD_COLOR);
    EXPECT_EQ(drawn.size(), cv::Size(4 * 128 + 3 * 8, 118));
    // Its first panel is the centre view (JPEG's few levels of loss allowed).
    const cv::Mat centre = cv::imread((training / "input_Cam040.png").string(), cv::IMREAD_COLOR);
    if (drawn.cols >= 128 && drawn.rows == 118) {
      EXPECT_LT(cv::norm(drawn(cv::Rect(0, 0, 128, 118)), centre, cv::NORM_L1) / (128 * 118 * 3),
                6.0);
    }
  }
  const auto unknown = testing::RunOnce(fmt::format("{} {} {} {} --scenes dino 2>&1", python,
                                                    script, benchmark.string(), out.string()));
  EXPECT_EQ(unknown.status, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("--scenes: dino not under"), std::string::npos) << unknown.output;
}

}  // namespace
}  // namespace lfcam::hci_benchmark_test
