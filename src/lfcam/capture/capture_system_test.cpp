// The capture system end to end, with real lfcam-node processes: simulated Pi modules driven by
// `lfcam capture` to a session that `calibrate` and `build` accept, holding the very images
// `lfcam simulate capture` writes; and a soak of consecutive shots on a full 10x10 array.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "lfcam/capture/array_status.h"
#include "lfcam/capture/capture_session.h"
#include "lfcam/capture/local_array_test_support.h"
#include "lfcam/cli/cli_test_support.h"
#include "lfcam/sim/test_capture.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using testing::Lfcam;
using testing::LocalArray;
using testing::TestTriggerMarginS;

TEST(CaptureSystem, SimulatedNodesShootASessionThatCalibrateAndBuildAccept) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("lfcam_capture_e2e_{}", ::getpid());
  LocalArray array(dir / "nodes", 2, 2,
                   {"--backend", "sim", "--sim-grid", "2x2", "--sim-seed", "1"});
  // The sim backend takes its position per node.
  for (int i = 0; i < array.size(); ++i)
    array.Start(i, {"--sim-position", fmt::format("{},{}", i / 2, i % 2)});
  const fs::path array_file = array.WriteArrayFile(648, 486);
  const std::string session = (dir / "session").string();
  auto run = Lfcam("capture configure " + array_file.string());
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("4 of 4 nodes ready"), std::string::npos) << run.output;
  // Eight of the simulator's 14 board poses are enough for calibrate (and keep the test short
  // under the sanitizers, where the nodes render slowly).
  for (int k = 0; k < 8; ++k) {
    run = Lfcam("capture shoot " + array_file.string() + " --session " + session +
                " --kind intrinsics --margin 0.1 --quiet");
    ASSERT_EQ(run.status, 0) << run.output;
  }
  for (const char* kind : {"world", "scene"}) {
    run = Lfcam("capture shoot " + array_file.string() + " --session " + session + " --kind " +
                kind + " --margin 0.1 --quiet --json");
    ASSERT_EQ(run.status, 0) << run.output;
    const auto report = nlohmann::json::parse(run.output);
    EXPECT_EQ(report["fired"], 4);
    EXPECT_EQ(report["complete"], true);
    EXPECT_LT(report["skew_ms"].get<double>(), 20.0);  // loose: a loaded, sanitized test machine
  }

  // The same images as the simulator writes directly, byte for byte.
  CaptureSimulationOptions o;
  o.rows = o.cols = 2;
  o.sensor_width = 648;
  o.sensor_height = 486;
  const fs::path reference = testing::SharedTestCapture("capture-system-2x2", o);
  const CaptureManifest shot = ReadManifest(session);
  std::size_t compared = 0;
  for (const Shot& s : shot.shots) {
    EXPECT_TRUE(s.pending.empty()) << s.name;
    for (const ShotImage& i : s.images) {
      EXPECT_EQ(Sha256OfFile(fs::path(session) / i.file), Sha256OfFile(reference / i.file))
          << i.file;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 10u * 4u);

  run = Lfcam("calibrate " + session + " --quiet --out " + (dir / "calibration.json").string());
  ASSERT_EQ(run.status, 0) << run.output;
  run = Lfcam("build " + session + " --calibration " + (dir / "calibration.json").string() +
              " --st-res 64x58 --quiet --out " + (dir / "built.lf").string());
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(fs::exists(dir / "built.lf"));
  fs::remove_all(dir);
}

TEST(CaptureSystem, ASoakOfConsecutiveShotsOnAFullArrayLosesNothing) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("lfcam_capture_soak_{}", ::getpid());
  fs::create_directories(dir / "replay");
  cv::Mat noise(240, 320, CV_8UC3);
  cv::randu(noise, 0, 255);
  cv::imwrite((dir / "replay" / "intrinsics.jpg").string(), noise);
  {
    LocalArray array(dir / "nodes", 10, 10,
                     {"--backend", "replay", "--replay", (dir / "replay").string()});
    array.StartAll();
    const ArrayConfig config = array.Config(320, 240);
    for (const NodeReport& r : ConfigureArray(config, array.key())) ASSERT_TRUE(r.ready());
    ShootOptions o;
    o.kind = ShotKind::kIntrinsics;
    // A hundred agents share this machine's two cores (ctest runs this suite alone: RUN_SERIAL in
    // CMakeLists.txt). On 2026-11-26 a shot came late three times in five runs: 13 agents by
    // 4 ms at a 0.3 s margin (another suite beside it), 71 by 23 ms at 0.5 s (the same), 2 by
    // 33 ms at 0.5 s alone. On an array each agent has its Pi to itself.
    o.margin_s = TestTriggerMarginS(1.0);
    constexpr int kShots = 8;
    double worst_skew_ms = 0;
    for (int k = 0; k < kShots; ++k) {
      const SessionReport r = ShootSession(config, array.key(), dir / "session", o);
      EXPECT_EQ(r.fired, 100) << "shot " << k;
      ASSERT_TRUE(r.problems.empty()) << r.problems.front().reason;
      worst_skew_ms = std::max(worst_skew_ms, r.skew_ms.value_or(1e9));
    }
    const CaptureManifest m = ReadManifest(dir / "session");
    ASSERT_EQ(m.shots.size(), std::size_t(kShots));
    const std::string expected = Sha256OfFile(dir / "replay" / "intrinsics.jpg");
    for (const Shot& s : m.shots) {
      ASSERT_EQ(s.images.size(), 100u) << s.name;
      for (const ShotImage& i : s.images)
        ASSERT_EQ(Sha256OfFile(dir / "session" / i.file), expected) << i.file;
    }
    // Every node still holds every capture (nothing is deleted without being asked).
    for (int i = 0; i < array.size(); ++i) {
      std::size_t held = 0;
      for (const auto& entry : fs::directory_iterator(array.captures(i)))
        held += entry.path().extension() == ".jpg";
      EXPECT_EQ(held, std::size_t(kShots)) << "node " << i;
    }
    RecordProperty("worst_skew_ms", std::to_string(worst_skew_ms));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam
