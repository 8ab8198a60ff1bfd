// End-to-end: `simulate capture` -> `calibrate` (and `calibrate intrinsics`) through the
// command, and their bad input: exit status 2 for flags, 1 for sessions, messages naming what.
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/sim/test_capture.h"

namespace {

namespace fs = std::filesystem;
using lfcam::testing::CommandResult;
using lfcam::testing::Lfcam;

class CalibrateCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("lfcam_calibrate_cli_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    // One session for every test process (simulated once per build), copied in: some tests
    // change their copy.
    lfcam::CaptureSimulationOptions o;
    o.rows = o.cols = 2;
    o.sensor_width = 648;
    o.sensor_height = 486;
    o.intrinsics_shots = 8;
    fs::copy(lfcam::testing::SharedTestCapture("cli-2x2", o), Path("session"),
             fs::copy_options::recursive);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    calibrated_.reset();
  }
  static std::string Path(const std::string& name) { return (*dir_ / name).string(); }
  // `calibrate` of the session, run once a suite by whichever test needs it first (the slowest
  // step here: 20 s under the sanitizers), writing cal.json and cal.png.
  static const CommandResult& Calibrated() {
    if (!calibrated_)
      calibrated_ =
          Lfcam("calibrate " + Path("session") + " --quiet --json --out " + Path("cal.json"));
    return *calibrated_;
  }
  static fs::path* dir_;
  static std::optional<CommandResult> calibrated_;
};
fs::path* CalibrateCli::dir_ = nullptr;
std::optional<CommandResult> CalibrateCli::calibrated_;

TEST_F(CalibrateCli, WritesTheCalibrationAndItsPicture) {
  const CommandResult& run = Calibrated();
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["format"], "lfcam-calibration");
  EXPECT_EQ(j["calibrated_cameras"], 4);
  EXPECT_EQ(j["cameras"].size(), 4u);
  EXPECT_LT(j["bundle_adjustment"]["final_rms_px"].get<double>(), 0.2);
  EXPECT_TRUE(fs::exists(Path("cal.json")));
  EXPECT_GT(fs::file_size(Path("cal.png")), 1000u);
  // The session layout is what docs/capture-layout.md says.
  EXPECT_TRUE(fs::exists(Path("session/calib/intrinsics/shot_07/cam_01_01.jpg")));
  EXPECT_TRUE(fs::exists(Path("session/calib/world/cam_00_01.jpg")));
  EXPECT_TRUE(fs::exists(Path("session/scene/cam_01_00.jpg")));
  EXPECT_TRUE(fs::exists(Path("session/ground_truth.json")));
}

TEST_F(CalibrateCli, SimulateCaptureWritesTheLayout) {
  const CommandResult run = Lfcam(
      "simulate capture --grid 1x2 --sensor 160x120 --shots 2 --quiet "
      "--seed 3 --out " +
      Path("tiny"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("8 images"), std::string::npos) << run.output;
  for (const char* file :
       {"manifest.json", "ground_truth.json", "calib/intrinsics/shot_01/cam_00_01.jpg",
        "calib/world/cam_00_00.jpg", "scene/cam_00_01.jpg"})
    EXPECT_TRUE(fs::exists(Path("tiny") + "/" + file)) << file;
  // Nothing is left beside it: the session was written under a temporary name and renamed.
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(*dir_))
    entries += entry.path().filename().string().rfind("tiny", 0) == 0;
  EXPECT_EQ(entries, 1);
}

// --lens-blur sets every module's point spread on the sensor: ground_truth.json gives it in each
// camera's pixels, and the blurred scene holds less fine detail than the same rig's through
// perfect lenses (the Laplacian's spread 11.7 against 21.9; 8 x 8 rays a pixel and no noise, as
// the paper scene's texture is far finer than these 160 x 120 pixels, and with 2 x 2 rays and the
// sensor's noise what the rays' draws and the noise add is most of it: 28.8 against 30.4).
TEST_F(CalibrateCli, SimulateCaptureBlursByTheLensAsked) {
  auto fine_detail = [&](const std::string& session) {
    cv::Mat grey, laplacian;
    cv::cvtColor(cv::imread(Path(session) + "/scene/cam_00_00.jpg"), grey, cv::COLOR_BGR2GRAY);
    cv::Laplacian(grey, laplacian, CV_64F);
    cv::Scalar mean, spread;
    cv::meanStdDev(laplacian, mean, spread);
    return spread[0];
  };
  double detail[2] = {0, 0};
  for (const int blurred : {0, 1}) {
    const std::string session = blurred ? "lens_blurred" : "lens_perfect";
    const CommandResult run = Lfcam(fmt::format(
        "simulate capture --grid 1x1 --sensor 160x120 --shots 1 --quiet --seed 3 --no-noise "
        "--supersampling 8 "
        "--lens-blur {} --out {}",
        blurred ? "11.2" : "0", Path(session)));
    ASSERT_EQ(run.status, 0) << run.output;
    std::ifstream truth(Path(session) + "/ground_truth.json");
    const auto j = nlohmann::json::parse(truth);
    // 11.2 um at 160 of the sensor's 2592 pixels of 1.4 um: 0.49 px.
    EXPECT_NEAR(j["cameras"][0]["lens_blur_px"].get<double>(), blurred ? 0.494 : 0.0, 0.001);
    detail[blurred] = fine_detail(session);
  }
  EXPECT_LT(detail[1], 0.8 * detail[0]) << "the Laplacian's spread, blurred against perfect";
}

TEST_F(CalibrateCli, CalibratesOneModuleFromItsImages) {
  std::string images;
  for (int k = 0; k < 8; ++k)
    images += Path("session/calib/intrinsics/shot_0" + std::to_string(k) + "/cam_00_00.jpg") + " ";
  const CommandResult run =
      Lfcam("calibrate intrinsics " + images + "--board 10x7@30 --json --out " + Path("cam.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_GE(j["images_used"].size(), 4u);
  EXPECT_LT(j["reprojection_rms_px"].get<double>(), 0.2);
  EXPECT_NEAR(j["intrinsics"]["fx"].get<double>(), 642.9, 0.03 * 642.9);  // 3.6 mm at 648 px
}

TEST_F(CalibrateCli, BadFlagsAreUsageErrors) {
  for (const std::string& args :
       {"calibrate " + Path("session") + " --out " + Path("x.json") + " --intrinsics-board 10x8@30",
        "calibrate " + Path("session") + " --out " + Path("x.json") + " --world-board abc",
        "calibrate " + Path("session"),
        "calibrate intrinsics " + Path("nothing.jpg") + " --board 10x7 --out " + Path("c.json"),
        "simulate capture --out " + Path("s2") + " --defects some",
        "simulate capture --out " + Path("s2") + " --board aruco",
        "simulate capture --out " + Path("s2") + " --board charuco --intrinsics-board 10x7@30",
        "simulate capture --out " + Path("s2") + " --intrinsics-board charuco:11x8@30/22",
        "simulate capture --out " + Path("s2") +
            " --board charuco --intrinsics-board "
            "charuco:11x8@30/29",
        "simulate capture --out " + Path("s2") + " --sensor 20x20",
        "simulate capture --out " + Path("s2") + " --lens-blur -1",
        "simulate capture --out " + Path("s2") + " --lens-blur 25",
        "simulate capture --out " + Path("session")}) {  // exists and is not empty
    const CommandResult run = Lfcam(args);
    EXPECT_EQ(run.status, 2) << args << "\n" << run.output;
  }
  EXPECT_FALSE(fs::exists(Path("s2")));
  EXPECT_FALSE(fs::exists(Path("x.json")));
}

TEST_F(CalibrateCli, BadSessionsAreErrorsNamingWhat) {
  CommandResult run = Lfcam("calibrate " + Path("none") + " --out " + Path("x.json"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("none"), std::string::npos) << run.output;
  fs::create_directories(Path("broken"));
  std::ofstream(Path("broken/manifest.json")) << "{\"format\": \"lfcam-capture\"}";
  run = Lfcam("calibrate " + Path("broken") + " --out " + Path("x.json"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("manifest.json"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(Path("x.json")));
  EXPECT_FALSE(fs::exists(Path("x.png")));
  // One module's images of two sizes: refused from their headers, naming the odd one.
  std::string images;
  for (int k = 0; k < 3; ++k)
    images += Path("session/calib/intrinsics/shot_0" + std::to_string(k) + "/cam_00_00.jpg") + " ";
  run = Lfcam("simulate capture --grid 1x1 --sensor 160x120 --shots 1 --quiet --out " +
              Path("small"));
  ASSERT_EQ(run.status, 0) << run.output;
  run = Lfcam("calibrate intrinsics " + images + Path("small/calib/world/cam_00_00.jpg") +
              " --board 10x7@30 --out " + Path("c.json"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("small/calib/world/cam_00_00.jpg: the image is 160x120, the first "
                            "was 648x486 (mixed sizes)"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(Path("c.json")));
}

TEST_F(CalibrateCli, BuildsTheLightFieldAndRecordsHowItWasMade) {
  ASSERT_EQ(Calibrated().status, 0) << Calibrated().output;
  CommandResult run = Lfcam("build " + Path("session") + " --calibration " + Path("cal.json") +
                            " --st-res 64x58 --quiet --json --out " + Path("built.lf"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["metadata"]["source"], "built");
  EXPECT_EQ(j["metadata"]["color_correction"]["applied"], true);
  EXPECT_EQ(j["metadata"]["filled_views"].size(), 0u);
  EXPECT_EQ(j["metadata"]["chroma_upsampling"], "guided");
  run = Lfcam("info --json " + Path("built.lf"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto info = nlohmann::json::parse(run.output);
  EXPECT_EQ(info["format_version"], 3);  // each view records its camera
  EXPECT_EQ(info["measured_poses"], true);
  EXPECT_EQ(info["view_cameras"], true);
  // The same array simulated directly from the true centres, and the two compared.
  run = Lfcam("simulate lightfield --grid 2x2 --st-res 64x58 --quiet --centers-from " +
              Path("session/ground_truth.json") + " --out " + Path("truth.lf"));
  ASSERT_EQ(run.status, 0) << run.output;
  run = Lfcam("compare --json " + Path("built.lf") + " " + Path("truth.lf"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto c = nlohmann::json::parse(run.output);
  // Tiny (a view of 64x58, from 648x486 images): the plumbing, not the accuracy (that is in
  // docs/fidelity.md). A view misplaced or flipped would be near 10 dB.
  EXPECT_GT(c["psnr_db"].get<double>(), 16.0);
  EXPECT_EQ(c["samples"], 4 * 64 * 58);
  run = Lfcam("compare --json " + Path("built.lf") + " " + Path("built.lf"));
  EXPECT_EQ(nlohmann::json::parse(run.output)["identical"], true);
}

TEST_F(CalibrateCli, BuildRefusesBadFlagsAndMismatches) {
  const std::string base = "build " + Path("session") + " --out " + Path("b.lf");
  for (const std::string& args :
       {base, base + " --calibration " + Path("c.json") + " --st-res 0x5",
        base + " --calibration " + Path("c.json") + " --st-domain 1,1,0,0",
        base + " --calibration " + Path("c.json") + " --compress lz4",
        base + " --calibration " + Path("c.json") + " --chroma fancy"}) {
    const CommandResult run = Lfcam(args);
    EXPECT_EQ(run.status, 2) << args << "\n" << run.output;
  }
  // A calibration that is not one, and centres for a different grid.
  std::ofstream(Path("not-a-calibration.json")) << "{\"format\": \"something\"}";
  CommandResult run = Lfcam(base + " --calibration " + Path("not-a-calibration.json"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("not-a-calibration.json"), std::string::npos) << run.output;
  run = Lfcam("simulate lightfield --grid 3x3 --st-res 8x8 --quiet --centers-from " +
              Path("session/ground_truth.json") + " --out " + Path("t3.lf"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("no centre for camera (0, 2)"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(Path("b.lf")));
  EXPECT_FALSE(fs::exists(Path("t3.lf")));
}

TEST_F(CalibrateCli, ASessionWithoutAManifestIsReadFromItsLayout) {
  fs::copy(Path("session"), Path("bare"), fs::copy_options::recursive);
  fs::remove(Path("bare/manifest.json"));
  CommandResult run = Lfcam("calibrate " + Path("bare") + " --quiet --out " + Path("bare.json"));
  EXPECT_EQ(run.status, 2) << run.output;  // the boards are not known
  EXPECT_NE(run.output.find("--intrinsics-board"), std::string::npos) << run.output;
  run = Lfcam("calibrate " + Path("bare") + " --intrinsics-board 10x7@30 --world-board 11x10@50" +
              " --quiet --out " + Path("bare.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  run = Lfcam("build " + Path("bare") + " --calibration " + Path("bare.json") +
              " --st-res 32x29 --quiet --out " + Path("bare.lf"));
  EXPECT_EQ(run.status, 0) << run.output;
}

}  // namespace
