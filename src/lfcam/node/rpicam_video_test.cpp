// Reading what rpicam-vid leaves behind, and the rpicam backend recording through a stand-in for
// rpicam-vid: a script that writes Motion-JPEG and its JSON metadata as rpicam-vid does.
#include "lfcam/node/rpicam_video.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "lfcam/core/error.h"
#include "lfcam/node/rpicam_camera.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

std::string Jpeg(const std::string& body) { return "\xFF\xD8" + body + "\xFF\xD9"; }

TEST(RpicamVideo, SplitsTheStreamAndPairsItsFramesWithTheirTimes) {
  const std::string stream = Jpeg("zero") + Jpeg("one") + Jpeg("two") + "\xFF\xD8" + "cut";
  const auto frames = SplitMjpeg(stream, "s");
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(stream.substr(frames[1].first, frames[1].second), Jpeg("one"));
  EXPECT_THROW(SplitMjpeg("no jpeg here", "s"), Error);

  const std::string meta = R"([
    {"SensorTimestamp": 1000000000, "FrameWallClock": 1800000000000000000, "ExposureTime": 9000,
     "ColourGains": [1.6, 1.5]},
    {"SensorTimestamp": 1033333333, "FrameWallClock": 1800000000033333333},
    {"SensorTimestamp": 1100000000, "FrameWallClock": 1800000000100000000}
  ])";
  const auto times = ParseRpicamMetadata(meta, "m");
  ASSERT_EQ(times.size(), 3u);
  EXPECT_EQ(times[2].wall_clock_ns, 1800000000100000000);
  // 30 fps: the third frame is two periods after the second, one was dropped.
  EXPECT_EQ(SequenceFromSensorTimes(times, 30), (std::vector<std::int64_t>{0, 1, 3}));
  // A camera stopped mid-write leaves the array open, the last object cut: the whole ones.
  EXPECT_EQ(ParseRpicamMetadata(meta.substr(0, meta.rfind("\"FrameWallClock\"")), "m").size(), 2u);
  EXPECT_EQ(ParseRpicamMetadata(meta.substr(0, meta.rfind(']')), "m").size(), 3u);
  EXPECT_THROW(ParseRpicamMetadata("{}", "m"), Error);
  EXPECT_THROW(ParseRpicamMetadata(R"([{"SensorTimestamp": 5}])", "m"), Error);
  EXPECT_THROW(ParseRpicamMetadata(R"([{"SensorTimestamp": 5, "FrameWallClock": 9},
                                       {"SensorTimestamp": 4, "FrameWallClock": 10}])",
                                   "m"),
               Error);
}

TEST(RpicamVideo, TheBackendRecordsThroughRpicamVidAndKeepsTheRecordingsFrames) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_rpicam_vid_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  // The stand-in: from its start, one frame a period for --timeout ms, each with its times; its
  // arguments saved for the test to read.
  const fs::path fake = dir / "fake-rpicam-vid";
  std::ofstream(fake) << R"(#!/bin/bash
echo "$@" > ")" << (dir / "args").string()
                      << R"("
while [ $# -gt 0 ]; do
  case $1 in
    --output) out=$2 ;; --metadata) meta=$2 ;; --framerate) fps=$2 ;; --timeout) ms=$2 ;;
  esac
  shift
done
period=$((1000000000 / fps))
t0=$(date +%s%N)
n=$(( ms * 1000000 / period ))
echo "[" > "$meta"
for ((k = 0; k < n; k++)); do
  t=$((t0 + k * period))
  [ $k -gt 0 ] && echo "," >> "$meta"
  printf '\xff\xd8frame %d\xff\xd9' $k >> "$out"
  echo "{\"SensorTimestamp\": $((5000000000 + k * period)), \"FrameWallClock\": $t}" >> "$meta"
done
echo "]" >> "$meta"
)";
  fs::permissions(fake, fs::perms::owner_all);
  RpicamOptions o;
  o.program = "unused";
  o.video_program = fake.string();
  o.work_folder = dir / "work";
  o.warmup_ms = 300;
  auto camera = MakeRpicamCamera(o);
  camera->Configure(CaptureSettings{});
  RecordRequest r;
  r.video.fps = 20;
  r.video.seconds = 0.5;
  r.video.width = 648;
  r.video.height = 486;
  r.video.sync = "client";
  EXPECT_EQ(camera->RecordLead(r.video).count(), 300 + 100 * 1000 / 20);
  r.video.sync = "off";
  const auto now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                       std::chrono::system_clock::now().time_since_epoch())
                       .count();
  r.start_unix_ns = now + 600'000'000;
  std::vector<CapturedFrame> frames;
  std::atomic<bool> stop{false};
  camera->Record(
      r, [&](CapturedFrame&& f) { frames.push_back(std::move(f)); }, stop);
  // The stand-in started 300 ms early and wrote a frame every 50 ms: the recording keeps the
  // ten whose times fall in the half second from the start, numbered from 0.
  ASSERT_GE(frames.size(), 9u);
  ASSERT_LE(frames.size(), 11u);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].sequence, std::int64_t(i));
    EXPECT_GE(frames[i].wall_clock_ns, r.start_unix_ns - 25'000'000);
    EXPECT_LT(frames[i].wall_clock_ns, r.start_unix_ns + 500'000'000);
    EXPECT_EQ(frames[i].jpeg.substr(0, 2), "\xFF\xD8");
  }
  std::ifstream args_file(dir / "args");
  const std::string args((std::istreambuf_iterator<char>(args_file)), {});
  EXPECT_NE(args.find("--codec mjpeg"), std::string::npos) << args;
  EXPECT_NE(args.find("--width 648 --height 486"), std::string::npos) << args;
  EXPECT_EQ(args.find("--sync"), std::string::npos) << args;  // sync off
  // High-speed mode needs a phase offset libcamera's sync does not have: refused, saying so.
  r.video.stagger_ns = 16'666'667;
  try {
    camera->Record(
        r, [](CapturedFrame&&) {}, stop);
    ADD_FAILURE() << "a staggered recording was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("staggered"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam
