// Recording on the array end to end, with real lfcam-node processes of the simulated backend:
// every camera's frames come home verified with their times, in step when synced; a node killed
// mid-recording is named, and `fetch` completes its recording once it is back.
#include "lfcam/capture/recording_session.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "lfcam/capture/array_status.h"
#include "lfcam/capture/local_array_test_support.h"
#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/image_io.h"
#include "lfcam/node/request_signature.h"
#include "lfcam/session/frame_alignment.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using testing::Lfcam;
using testing::LocalArray;
using testing::TestTriggerMarginS;

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A 2x2 array of simulated nodes, configured.
struct SimulatedArrayOfNodes {
  explicit SimulatedArrayOfNodes(const fs::path& dir, const std::vector<std::string>& extra = {})
      : nodes(dir / "nodes", 2, 2, {"--backend", "sim", "--sim-grid", "2x2", "--sim-seed", "3"}) {
    for (int i = 0; i < nodes.size(); ++i) Start(i, extra);
    config = nodes.Config(320, 240);
    for (const NodeReport& r : ConfigureArray(config, nodes.key())) EXPECT_TRUE(r.ready());
  }
  void Start(int i, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> flags = {"--sim-position", fmt::format("{},{}", i / 2, i % 2)};
    flags.insert(flags.end(), extra.begin(), extra.end());
    nodes.Start(i, flags);
  }
  LocalArray nodes;
  ArrayConfig config;
};

// A short recording at 10 fps in a small video mode, soon.
RecordOptions SmallRecording(double seconds) {
  RecordOptions o;
  o.seconds = seconds;
  o.fps = 10;
  o.width = 160;
  o.height = 120;
  o.margin_s = TestTriggerMarginS(0.3);
  return o;
}

TEST(RecordSession, SimulatedNodesRecordInStepAndEveryFrameComesHomeWithItsTime) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("lfcam_record_{}", ::getpid());
  SimulatedArrayOfNodes array(dir, {"--sim-drop-rate", "0"});
  RecordOptions o = SmallRecording(1.0);
  const SessionReport report = RecordSession(array.config, array.nodes.key(), dir / "session", o);
  EXPECT_EQ(report.fired, 4);
  EXPECT_TRUE(report.problems.empty()) << report.problems.front().reason;

  const CaptureManifest m = ReadManifest(dir / "session");
  ASSERT_EQ(m.shots.size(), 1u);
  const Shot& shot = m.shots[0];
  EXPECT_EQ(shot.kind, ShotKind::kVideo);
  EXPECT_EQ(shot.name, "rec_00");
  ASSERT_TRUE(shot.video);
  EXPECT_EQ(shot.video->sync, "on");
  ASSERT_EQ(shot.images.size(), 4u);
  const std::int64_t t0 = shot.video->start_unix_ns;
  for (const ShotImage& image : shot.images) {
    EXPECT_EQ(image.file,
              fmt::format("video/rec_00/cam_{:02d}_{:02d}.mjpeg", image.row, image.col));
    EXPECT_EQ(image.capture["recording"], "complete");
    ASSERT_EQ(image.frames.size(), 10u);
    const std::string stream = ReadBytes(dir / "session" / image.file);
    EXPECT_EQ(Sha256Hex(stream), image.capture["sha256"]);
    EXPECT_EQ(stream.size(), image.frames.back().offset + image.frames.back().size);
    for (std::size_t k = 0; k < image.frames.size(); ++k) {
      const FrameTime& f = image.frames[k];
      EXPECT_EQ(f.sequence, std::int64_t(k));
      // Synced: on the 100 ms grid from the start, within the sync error (30 us).
      EXPECT_NEAR(double(f.wall_clock_ns - t0), k * 100e6, 30e3 + 1);
      const std::string_view jpeg = std::string_view(stream).substr(f.offset, f.size);
      const cv::Mat frame = DecodeImageBytes(
          {reinterpret_cast<const std::uint8_t*>(jpeg.data()), jpeg.size()}, "frame");
      EXPECT_EQ(frame.cols, 160);
      EXPECT_EQ(frame.rows, 120);
    }
  }
  // The scene moves: the first and the last frame of a camera differ (the ball came in).
  const ShotImage& first = shot.images[0];
  const std::string stream = ReadBytes(dir / "session" / first.file);
  auto decode = [&](const FrameTime& f) {
    return DecodeImageBytes(
        {reinterpret_cast<const std::uint8_t*>(stream.data()) + f.offset, f.size}, "frame");
  };
  cv::Mat diff;
  cv::absdiff(decode(first.frames.front()), decode(first.frames.back()), diff);
  EXPECT_GT(cv::countNonZero(diff.reshape(1) > 40), 10);

  // The report: ten light field frames, each of four cameras, in step to the sync error.
  auto run = Lfcam(fmt::format("capture report --session {} --json --out {}",
                               (dir / "session").string(), (dir / "sync.png").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto report_json = nlohmann::json::parse(run.output);
  EXPECT_EQ(report_json["frames"], 10);
  EXPECT_EQ(report_json["camera_frames_missing"], 0);
  EXPECT_LE(report_json["spread_us"]["max"].get<double>(), 60.0 + 1e-3);
  EXPECT_EQ(report_json["per_frame"][9]["cameras"], 4);
  EXPECT_TRUE(fs::is_regular_file(dir / "sync.png"));
  // Beside the nodes' health, how each recording kept in step.
  const fs::path array_file = array.nodes.WriteArrayFile(320, 240);
  run = Lfcam(fmt::format("capture status {} --session {} --json", array_file.string(),
                          (dir / "session").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto status_json = nlohmann::json::parse(run.output);
  EXPECT_EQ(status_json["nodes"].size(), 4u);
  ASSERT_EQ(status_json["recordings"].size(), 1u);
  EXPECT_EQ(status_json["recordings"][0]["shot"], "rec_00");
  EXPECT_FALSE(status_json["recordings"][0].contains("per_frame"));
  run = Lfcam(fmt::format("capture report --session {} --shot rec_07", (dir / "session").string()));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("no recording 'rec_07'"), std::string::npos) << run.output;
  fs::remove_all(dir);
}

// High-speed mode: two interleaved groups, the second's frames half a period later; together
// twice the light field frames, each of one group.
TEST(RecordSession, StaggeredGroupsSampleTimeTwiceAsOften) {
  const fs::path dir =
      fs::temp_directory_path() / fmt::format("lfcam_record_stagger_{}", ::getpid());
  SimulatedArrayOfNodes array(dir, {"--sim-drop-rate", "0"});
  RecordOptions o = SmallRecording(0.5);
  o.stagger = 2;
  const SessionReport report = RecordSession(array.config, array.nodes.key(), dir / "session", o);
  EXPECT_TRUE(report.problems.empty()) << report.problems.front().reason;
  const CaptureManifest m = ReadManifest(dir / "session");
  const Shot& shot = m.shots.back();
  EXPECT_EQ(shot.video->groups, 2);
  for (const ShotImage& image : shot.images) {
    const int group = (image.row + image.col) % 2;
    EXPECT_EQ(image.capture["group"], group);
    EXPECT_NEAR(double(image.frames[0].wall_clock_ns - shot.video->start_unix_ns), group * 50e6,
                30e3 + 1);
  }
  const FrameAlignment a = AlignFrames(shot, 2, 2);
  ASSERT_EQ(a.frames.size(), 10u);
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    EXPECT_EQ(a.frames[k].cameras, 2) << k;
    EXPECT_NEAR(double(a.frames[k].time_ns - a.frames[0].time_ns), double(k) * 50e6, 1e5);
  }
  fs::remove_all(dir);
}

TEST(RecordSession, ANodeKilledMidRecordingIsNamedAndFetchCompletesItWhenItIsBack) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("lfcam_record_kill_{}", ::getpid());
  SimulatedArrayOfNodes array(dir);
  RecordOptions o = SmallRecording(3.0);
  // Half way through the recording, which starts the trigger margin from now.
  std::thread killer([&] {
    std::this_thread::sleep_for(std::chrono::duration<double>(o.margin_s + 1.5));
    array.nodes.Kill(3);  // camera (1, 1), SIGKILL: no chance to close its recording
  });
  const SessionReport report = RecordSession(array.config, array.nodes.key(), dir / "session", o);
  killer.join();
  ASSERT_EQ(report.problems.size(), 1u);
  EXPECT_EQ(report.problems[0].row, 1);
  EXPECT_EQ(report.problems[0].col, 1);
  EXPECT_EQ(report.problems[0].status, "captured");
  // Named with its node and why: it does not answer.
  EXPECT_NE(report.problems[0].reason.find(array.nodes.address(3)), std::string::npos)
      << report.problems[0].reason;
  EXPECT_EQ(report.images_ok, 3);

  // Back, it closes what it recorded; fetch asks for it and brings it home.
  array.Start(3);
  const SessionReport fetched = FetchSession(array.config, array.nodes.key(), dir / "session", {});
  EXPECT_TRUE(fetched.problems.empty()) << fetched.problems.front().reason;
  EXPECT_EQ(fetched.images_ok, 4);
  const CaptureManifest m = ReadManifest(dir / "session");
  const ShotImage& killed = m.shots[0].images[3];
  EXPECT_EQ(killed.capture["recording"], "truncated");
  EXPECT_GT(killed.frames.size(), 3u);
  EXPECT_LT(killed.frames.size(), 25u);
  const std::string stream = ReadBytes(dir / "session" / killed.file);
  EXPECT_EQ(stream.size(), killed.frames.back().offset + killed.frames.back().size);
  for (const ShotImage& image : m.shots[0].images) {
    if (&image == &killed) continue;
    EXPECT_GE(image.frames.size(), 27u);  // 30 less a few dropped
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam
