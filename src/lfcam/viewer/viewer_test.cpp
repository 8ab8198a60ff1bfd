// The viewer for real: `lfcam view` in a window under Xvfb, driven by a script (set parameters,
// click to focus, wait, save a screenshot, quit), checked against `lfcam render` and the scene's
// truth; and bad input refused before any window opens. Without xvfb-run the test says so and
// skips, unless LFCAM_REQUIRE_GL=1 (scripts/test.sh, which installs it), where that fails.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/cli/share_test_support.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/image_metrics.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::Lfcam;
using testing::RunOnce;

bool Required() { return testing::GlRequired(); }

bool HaveXvfb() { return RunOnce("command -v xvfb-run >/dev/null 2>&1").status == 0; }

// `lfcam view ARGS` in a virtual X server. Under the asan preset without LeakSanitizer: Mesa's
// software driver leaves 240 bytes allocated at exit from code it has unloaded by then (so the
// report has no names to suppress it by); lfcam's own code is leak-checked by every other test.
// The status is lfcam's own, printed after it exits: xvfb-run's replaces it with 5 when its
// temporary folder cannot be removed afterwards (seen under load, with lfcam's output right).
CommandResult View(const std::string& args) {
  static const std::string kStatus = "lfcam-view-exit-status=";
  const char* asan = std::getenv("ASAN_OPTIONS");
  std::string command = "ASAN_OPTIONS='";
  command.append(asan ? asan : "")
      .append(":detect_leaks=0' xvfb-run -a -s '-screen 0 1280x1024x24' sh -c '");
  command.append(LFCAM_CLI_PATH)
      .append(" view ")
      .append(args)
      .append(" 2>&1; echo ")
      .append(kStatus)
      .append("$?' 2>&1");
  CommandResult run = RunOnce(command);
  const auto at = run.output.rfind(kStatus);
  if (at != std::string::npos) {
    run.status = std::atoi(run.output.c_str() + at + kStatus.size());
    run.output.erase(at);
  }
  return run;
}

class Viewer : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One directory per process: ctest runs each suite in its own process, in parallel.
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("lfcam_viewer_test_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    // The paper's array over the world board, fine enough to focus on the globe.
    const CommandResult run = Lfcam(
        "simulate lightfield --scene paper --st-res 312x288 --supersampling 1 --quiet --out " +
        (*dir_ / "paper.lf").string());
    ASSERT_EQ(run.status, 0) << run.output;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  void SetUp() override {
    if (!HaveXvfb()) {
      if (Required()) FAIL() << "LFCAM_REQUIRE_GL=1 but xvfb-run is not installed";
      GTEST_SKIP() << "xvfb-run is not installed: the viewer needs a (virtual) screen";
    }
  }
  static std::string Path(const std::string& name) { return (*dir_ / name).string(); }
  static void Write(const std::string& name, const std::string& text) {
    std::ofstream(Path(name)) << text;
  }
  static fs::path* dir_;
};
fs::path* Viewer::dir_ = nullptr;

TEST_F(Viewer, ScriptedSessionFocusesOnTheGlobeAndItsScreenshotRendersAgainOffline) {
  // The camera at the array's centre looks at the globe's centre (370, 165, -300): the globe's
  // front is then on the window's centre, at 3902.2 - 90 = 3812.2 mm along the view.
  Write("session.script",
        "window 320 240\n"
        "set integrator cameras\n"
        "set aperture 40\n"
        "set focal-length 300\n"
        "set look-at 370,165,-300\n"
        "wait\n"
        "click 160 120\n"
        "wait\n"
        "print\n"
        "key F1\n"
        "key F2\n"
        "screenshot " +
            Path("shot.png") +
            "\n"
            "capture " +
            Path("window.png") +
            "\n"
            "quit\n");
  const CommandResult run =
      View(Path("paper.lf") + " --script " + Path("session.script") + " --window 320x240");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("lfcam view: "), std::string::npos) << run.output;

  // Click to focus landed on the globe.
  const auto line = run.output.find("{\"camera\"");
  ASSERT_NE(line, std::string::npos) << run.output;
  const auto view =
      nlohmann::json::parse(run.output.substr(line, run.output.find('\n', line) - line));
  const double focus = view["camera"]["focus_distance_mm"].get<double>();
  EXPECT_NEAR(focus, 3812.2, 0.02 * 3812.2) << run.output;
  EXPECT_EQ(view["render"]["integrator"], "cameras");

  // The screenshot and its view file re-render offline to the same picture.
  ASSERT_TRUE(fs::exists(Path("shot.png"))) << run.output;
  ASSERT_TRUE(fs::exists(Path("shot.json"))) << run.output;
  ASSERT_TRUE(fs::exists(Path("window.png"))) << run.output;
  const CommandResult again = Lfcam("render " + Path("paper.lf") + " --camera " +
                                    Path("shot.json") + " --out " + Path("again.png") + " --quiet");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("cameras integrator"), std::string::npos) << again.output;
  const auto same = nlohmann::json::parse(
      Lfcam("compare --json " + Path("shot.png") + " " + Path("again.png")).output);
  // (Identical images have an infinite PSNR, written as null.)
  if (!same["psnr_db"].is_null()) {
    EXPECT_GE(same["psnr_db"].get<double>(), 40.0) << same.dump();
  }
  std::cout << "clicked focus " << focus << " mm (truth 3812.2 mm); the screenshot against "
            << "render --camera: " << same.dump() << "\n";
  // ... and at another size, from the same view.
  const CommandResult larger =
      Lfcam("render " + Path("paper.lf") + " --camera " + Path("shot.json") +
            " --size 640x480 --out " + Path("larger.png") + " --quiet");
  ASSERT_EQ(larger.status, 0) << larger.output;
  EXPECT_NE(larger.output.find("640x480"), std::string::npos) << larger.output;
}

TEST_F(Viewer, AccumulatesCostlyLensSampleFramesToWhatRenderWrites) {
  // A frame budget of 1 ms: once a full lens-samples frame has been timed, the next view comes
  // in parts (ranges of lens samples), accumulated; the screenshot is the frame on screen.
  Write("lens.script",
        "window 320 240\n"
        "set integrator lens-samples\n"
        "set aperture 150\n"
        "set lens-rate 4\n"
        "wait\n"
        "set focus-distance 3700\n"
        "wait\n"
        "screenshot " +
            Path("lens.png") +
            "\n"
            "quit\n");
  const CommandResult run = View(Path("paper.lf") + " --script " + Path("lens.script") +
                                 " --window 320x240 --frame-budget 1");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("lens samples accumulated in"), std::string::npos) << run.output;
  const CommandResult again = Lfcam("render " + Path("paper.lf") + " --camera " +
                                    Path("lens.json") + " --out " + Path("lens_again.png"));
  ASSERT_EQ(again.status, 0) << again.output;
  const auto same = nlohmann::json::parse(
      Lfcam("compare --json " + Path("lens.png") + " " + Path("lens_again.png")).output);
  if (!same["psnr_db"].is_null()) {
    EXPECT_GE(same["psnr_db"].get<double>(), 40.0) << same.dump();
  }
  std::cout << run.output << "accumulated against render --camera: " << same.dump() << "\n";
}

// Without the suite's paper.lf: a small array of its own.
class ViewerWithDepth : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!HaveXvfb()) {
      if (Required()) FAIL() << "LFCAM_REQUIRE_GL=1 but xvfb-run is not installed";
      GTEST_SKIP() << "xvfb-run is not installed: the viewer needs a (virtual) screen";
    }
    dir_ = fs::temp_directory_path() / ("lfcam_viewer_depth_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  void Write(const std::string& name, const std::string& text) const {
    std::ofstream(Path(name)) << text;
  }
  fs::path dir_;
};

TEST_F(ViewerWithDepth, OffersTheDepthLookupAndItsScreenshotRendersAgainOffline) {
  // A small array with the simulator's true depth maps (what `lfcam depth --all` estimates).
  const CommandResult made = Lfcam(
      "simulate lightfield --scene paper --grid 4x4 --st-res 156x144 --supersampling 1 --quiet "
      "--out " +
      Path("small.lf") + " --depth-out " + Path("small_depth"));
  ASSERT_EQ(made.status, 0) << made.output;
  Write("depth.script",
        "window 160 120\n"
        "set integrator lens-samples\n"
        "set interpolation depth\n"
        "set focal-length 300\n"
        "wait\n"
        "screenshot " +
            Path("depth.png") +
            "\n"
            "quit\n");
  CommandResult run = View(Path("small.lf") + " --depth " + Path("small_depth") + " --script " +
                           Path("depth.script") + " --window 160x120");
  ASSERT_EQ(run.status, 0) << run.output;
  const CommandResult again =
      Lfcam("render " + Path("small.lf") + " --camera " + Path("depth.json") + " --depth " +
            Path("small_depth") + " --out " + Path("depth_again.png"));
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("depth lookup"), std::string::npos) << again.output;
  const auto same = nlohmann::json::parse(
      Lfcam("compare --json " + Path("depth.png") + " " + Path("depth_again.png")).output);
  if (!same["psnr_db"].is_null()) {
    EXPECT_GE(same["psnr_db"].get<double>(), 40.0) << same.dump();
  }
  // Without depth maps the lookup is refused, naming the flag.
  run = View(Path("small.lf") + " --script " + Path("depth.script") + " --window 160x120");
  EXPECT_NE(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("--depth"), std::string::npos) << run.output;
}

// An imported rectified rig in assumed units: the viewer opens on the rig's central camera (its
// own field of view and principal point, no breathing), so its first frame is that camera's
// photograph.
TEST_F(Viewer, OpensAnImportedRigAsItsCentralCamera) {
  fs::create_directories(Path("rig"));
  cv::Mat texture(96 * 3, 128 * 3, CV_8UC3);
  cv::randu(texture, 0, 255);
  cv::GaussianBlur(texture, texture, {0, 0}, 1.5);
  for (int r = 1; r <= 3; ++r)
    for (int c = 1; c <= 3; ++c)  // a plane at the zero-disparity distance: the same pixels
      cv::imwrite(Path(fmt::format("rig/v_{:02d}_{:02d}.png", r, c)),
                  texture(cv::Rect(128, 96, 128, 96)) + cv::Scalar(r, c, 0));
  CommandResult run = Lfcam("import " + Path("rig") + " --out " + Path("rig.lf") + " --quiet");
  ASSERT_EQ(run.status, 0) << run.output;
  Write("rig.script",
        "window 128 96\n"
        "wait\n"
        "print\n"
        "screenshot " +
            Path("rig_shot.png") + "\ncamera 0 2\nwait\nscreenshot " + Path("rig_corner.png") +
            "\ncamera 0.5 2\nwait\nscreenshot " + Path("rig_between.png") +
            "\nclick 64 48\nwait\nkey F2\ncapture " + Path("rig_window.png") + "\nquit\n");
  run = View(Path("rig.lf") + " --script " + Path("rig.script") + " --window 128x96");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto line = run.output.find("{\"camera\"");
  ASSERT_NE(line, std::string::npos) << run.output;
  const auto view =
      nlohmann::json::parse(run.output.substr(line, run.output.find('\n', line) - line));
  EXPECT_EQ(view["camera"]["breathing"], false) << view.dump();
  const auto photo = cv::imread(Path("rig/v_02_02.png")), shot = cv::imread(Path("rig_shot.png"));
  ASSERT_EQ(shot.size(), photo.size());
  EXPECT_LE(cv::norm(shot, photo, cv::NORM_INF), 1) << view.dump();
  // Stood as the rig's corner camera (lfcam's row 0 is the names' last row): its photograph;
  // halfway to the next camera, between the two.
  const auto corner = cv::imread(Path("rig/v_03_03.png"));
  EXPECT_LE(cv::norm(cv::imread(Path("rig_corner.png")), corner, cv::NORM_INF), 1);
  const auto above = cv::imread(Path("rig/v_02_03.png"));
  cv::Mat between;
  cv::addWeighted(corner, 0.5, above, 0.5, 0, between);
  EXPECT_LE(cv::norm(cv::imread(Path("rig_between.png")), between, cv::NORM_INF), 2);
  // Lengths in the rig's own unit (no scale was given): click to focus says so, as info does.
  EXPECT_NE(run.output.find(" units at (64, 48)"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(" mm at ("), std::string::npos) << run.output;
  // A light field without its cameras, or a camera off the grid, is refused naming the line.
  Write("off.script", "camera 5 0\nquit\n");
  run = View(Path("rig.lf") + " --script " + Path("off.script") + " --window 128x96");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("off.script:1"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("outside the 3x3 grid"), std::string::npos) << run.output;
}

TEST_F(Viewer, RefusesMissingOrCorruptFilesBeforeAnyWindow) {
  CommandResult run = View(Path("missing.lf"));
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("missing.lf"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("lfcam view: "), std::string::npos) << run.output;  // no window

  Write("corrupt.lf", "LFCAM-LF but not really a light field");
  run = View(Path("corrupt.lf"));
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("corrupt.lf"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("lfcam view: "), std::string::npos) << run.output;

  Write("bad.script", "set aperture\n");
  run = View(Path("paper.lf") + " --script " + Path("bad.script"));
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("bad.script:1"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("lfcam view: "), std::string::npos) << run.output;

  run = View(Path("paper.lf") + " --backend vulkan");
  EXPECT_EQ(run.status, 2) << run.output;
}

// A light field video plays: seek, play (looping), the frame shown is the file's frame; pause,
// step, and the keys. Each screenshot is `lfcam render --frame K` of its saved view.
TEST_F(Viewer, PlaysALightFieldVideoAndEveryFrameShownIsTheFilesFrame) {
  const fs::path inputs = testing::SharedSharingLightFields();  // moving.lfv: 3 frames, 2 fps
  Write("play.script",
        "window 192 128\n"
        "set focal-length 250\n"
        "seek 2\n"
        "wait\n"
        "screenshot " +
            Path("frame2.png") +
            "\n"
            "play\n"
            "wait-frame 1\n"
            "print\n"
            "pause\n"
            "step 1\n"
            "wait\n"
            "print\n"
            "screenshot " +
            Path("stepped.png") +
            "\n"
            "key Space\n"
            "frames 2\n"
            "print\n"
            "key Space\n"
            "key Home\n"
            "wait\n"
            "print\n"
            "quit\n");
  const CommandResult run = View((inputs / "moving.lfv").string() + " --script " +
                                 Path("play.script") + " --window 192x128");
  ASSERT_EQ(run.status, 0) << run.output;
  std::vector<nlohmann::json> printed;
  std::istringstream lines(run.output);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line[0] == '{') printed.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(printed.size(), 4u) << run.output;
  EXPECT_EQ(printed[0]["video"]["frame"], 1) << "played on from 2, looped to 0, then 1";
  EXPECT_EQ(printed[0]["video"]["playing"], true);
  EXPECT_EQ(printed[0]["video"]["frames"], 3);
  EXPECT_EQ(printed[1]["video"]["frame"], 2) << "a step on from 1";
  EXPECT_EQ(printed[1]["video"]["playing"], false);
  EXPECT_EQ(printed[2]["video"]["playing"], true) << "space plays";
  EXPECT_EQ(printed[3]["video"]["frame"], 0) << "Home";
  EXPECT_EQ(printed[3]["video"]["playing"], false) << "space again pauses";
  // The screenshots are the file's frame 2, rendered offline through the same view.
  for (const std::string name : {"frame2", "stepped"}) {
    const std::string again = Path(name + "_again.png"), other = Path(name + "_other.png");
    ASSERT_EQ(Lfcam(fmt::format("render {} --frame 2 --camera {} --out {} --quiet",
                                (inputs / "moving.lfv").string(), Path(name + ".json"), again))
                  .status,
              0);
    ASSERT_EQ(Lfcam(fmt::format("render {} --frame 0 --camera {} --out {} --quiet",
                                (inputs / "moving.lfv").string(), Path(name + ".json"), other))
                  .status,
              0);
    const cv::Mat shot = ReadImageSrgb8(Path(name + ".png"));
    EXPECT_EQ(CompareImages(shot, ReadImageSrgb8(again)).mean_abs_error, 0.0) << name;
    EXPECT_GT(CompareImages(shot, ReadImageSrgb8(other)).mean_abs_error, 0.2) << name;
  }
}

TEST_F(Viewer, DepthMapsDoNotGoWithAVideo) {
  const fs::path inputs = testing::SharedSharingLightFields();
  const CommandResult run = View((inputs / "moving.lfv").string() + " --depth " + Path("nowhere"));
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("depth maps belong to one light field frame"), std::string::npos)
      << run.output;
}

}  // namespace
}  // namespace lfcam
