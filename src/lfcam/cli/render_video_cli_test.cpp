// `lfcam render --video` as a user runs it: a focus sweep and a path through saved views of a
// still light field, the frames of a light field video, each frame checked against `lfcam
// render` of the same camera; and every way to ask for a video that makes no sense.
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/cli/share_test_support.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/image_metrics.h"
#include "lfcam/core/test_support.h"
#include "lfcam/share/mp4_test_support.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using testing::Lfcam;

// A frame against its render: H.264 at crf 10 and 4:2:0 chroma on these small, sharp frames.
constexpr double kEncoded = 32.0;
// The whole scene in view (the fan and the ball move).
constexpr const char* kWide = "--size 192x128 --focal-length 250";

class RenderVideoCli : public testing::SharingTest {
 protected:
  // Frame `k` of the video against `lfcam render` of the same light field with `flags`.
  static double FramePsnr(const testing::DecodedMp4& video, int k, const std::string& input,
                          const std::string& flags) {
    const std::string png = Path(fmt::format("check_{}.png", k));
    const auto run = Lfcam(fmt::format("render {} {} --out {} --quiet", input, flags, png));
    EXPECT_EQ(run.status, 0) << run.output;
    return CompareImages(video.frames.at(std::size_t(k)), ReadImageSrgb8(png)).psnr_db;
  }
};

TEST_F(RenderVideoCli, AFocusSweepIsTheRendersOfItsFrames) {
  const std::string out = Path("sweep.mp4");
  const std::string lens = "--size 128x96 --aperture 120 --integrator cameras-quadrilinear";
  const auto run = Lfcam(fmt::format(
      "render {} {} --focus-distance 3400:5200 --frames 7 --fps 24 --crf 10 --video {} --quiet",
      Input("still.lf"), lens, out));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("7 frames of 128x96 at 24 fps"), std::string::npos) << run.output;
  const testing::DecodedMp4 video = testing::DecodeMp4(out);
  ASSERT_EQ(video.frames.size(), 7u);
  EXPECT_NEAR(video.fps, 24.0, 1e-6);
  // Frames 0, 3 and 6 are the renders at 3400, 4300 and 5200 mm (the encoder's loss only).
  for (const auto& [k, distance] : {std::pair{0, 3400}, {3, 4300}, {6, 5200}})
    EXPECT_GT(FramePsnr(video, k, Input("still.lf"),
                        fmt::format("{} --focus-distance {}", lens, distance)),
              kEncoded)
        << k;
  // ... and not each other: the sweep really refocuses.
  EXPECT_LT(CompareImages(video.frames[0], video.frames[6]).psnr_db, 30.0);
}

// FFmpeg and the codec libraries it brings are opened when a video is written, not at every
// start (share/ffmpeg_library.h): the loader's own account of the files it opens says so.
TEST_F(RenderVideoCli, OpensFfmpegOnlyToWriteAVideo) {
  const auto loaded = [](const std::string& args) {
    return testing::RunOnce(fmt::format("LD_DEBUG=files {} {} 2>&1", LFCAM_CLI_PATH, args));
  };
  const auto still = loaded(
      fmt::format("render {} --size 64x48 --out {} --quiet", Input("still.lf"), Path("a.png")));
  ASSERT_EQ(still.status, 0) << still.output;
  ASSERT_NE(still.output.find("file=libopencv_core.so"), std::string::npos) << still.output;
  EXPECT_EQ(still.output.find("libavformat"), std::string::npos);
  EXPECT_EQ(still.output.find("libavcodec"), std::string::npos);
  const auto video =
      loaded(fmt::format("render {} --size 64x48 --focus-distance 3400:5200 --frames 2 --video {} "
                         "--quiet",
                         Input("still.lf"), Path("a.mp4")));
  ASSERT_EQ(video.status, 0) << video.output;
  EXPECT_NE(video.output.find("file=libavformat.so"), std::string::npos);
  EXPECT_NE(video.output.find("dynamically loaded by"), std::string::npos);
  EXPECT_EQ(testing::DecodeMp4(Path("a.mp4")).frames.size(), 2u);
  // Where FFmpeg cannot be opened (here a file that is no library stands in its place), the
  // video is refused saying which package to install, as an error of the machine, not a flag;
  // nothing is written.
  fs::create_directories(Path("no_ffmpeg"));
  std::ofstream(Path(fmt::format("no_ffmpeg/libavformat.so.{}", LIBAVFORMAT_VERSION_MAJOR)))
      << "not a library\n";
  const auto refused = testing::RunOnce(fmt::format(
      "LD_LIBRARY_PATH={} {} render {} --size 64x48 --focus-distance 3400:5200 --frames 2 "
      "--video {} --quiet 2>&1",
      Path("no_ffmpeg"), LFCAM_CLI_PATH, Input("still.lf"), Path("b.mp4")));
  EXPECT_EQ(refused.status, 1) << refused.output;
  EXPECT_NE(refused.output.find("apt-get install libavformat"), std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(Path("b.mp4")));
}

TEST_F(RenderVideoCli, APathPassesThroughItsSavedViews) {
  const auto view = [&](const std::string& name, double x, double focus) {
    std::ofstream(Path(name)) << fmt::format(
        R"({{"format": "lfcam-view", "version": 1, "camera": {{"width": 96, "height": 64,
        "eye": [{}, 270, 3600], "look_at": [300, 270, -700], "up": [0, 1, 0],
        "focal_length_mm": 600, "focus_distance_mm": {}, "aperture_mm": 0, "lens_rate": 4,
        "breathing": true}}, "render": {{"integrator": "lens-samples",
        "interpolation": "quadrilinear"}}}})",
        x, focus);
  };
  view("a.json", 200, 4000);
  view("b.json", 300, 4300);
  view("c.json", 400, 4000);
  const std::string out = Path("path.mp4");
  const auto run =
      Lfcam(fmt::format("render {} --path {},{},{} --frames 9 --crf 10 --video {}",
                        Input("still.lf"), Path("a.json"), Path("b.json"), Path("c.json"), out));
  ASSERT_EQ(run.status, 0) << run.output;
  const testing::DecodedMp4 video = testing::DecodeMp4(out);
  ASSERT_EQ(video.frames.size(), 9u);
  EXPECT_NEAR(video.fps, 30.0, 1e-6);
  EXPECT_GT(FramePsnr(video, 0, Input("still.lf"), "--camera " + Path("a.json")), kEncoded);
  EXPECT_GT(FramePsnr(video, 4, Input("still.lf"), "--camera " + Path("b.json")), kEncoded);
  EXPECT_GT(FramePsnr(video, 8, Input("still.lf"), "--camera " + Path("c.json")), kEncoded);
  // Flags given override every view: the same path at another size.
  const auto resized =
      Lfcam(fmt::format("render {} --path {},{} --size 64x48 --frames 2 --video {}",
                        Input("still.lf"), Path("a.json"), Path("c.json"), Path("small.mp4")));
  ASSERT_EQ(resized.status, 0) << resized.output;
  EXPECT_EQ(testing::DecodeMp4(Path("small.mp4")).frames.at(0).size(), cv::Size(64, 48));
}

TEST_F(RenderVideoCli, AVideoPlaysItsFramesAtItsRate) {
  const std::string out = Path("moving.mp4");
  const auto run =
      Lfcam(fmt::format("render {} {} --crf 0 --video {}", Input("moving.lfv"), kWide, out));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("3 frames of 192x128 at 2 fps"), std::string::npos) << run.output;
  const testing::DecodedMp4 video = testing::DecodeMp4(out);
  ASSERT_EQ(video.frames.size(), 3u);
  EXPECT_NEAR(video.fps, 2.0, 1e-6);
  for (int k = 0; k < 3; ++k) {
    const double own =
        FramePsnr(video, k, Input("moving.lfv"), fmt::format("{} --frame {}", kWide, k));
    EXPECT_GT(own, kEncoded) << k;
    // The scene moves: frame k is its own light field frame, not another's.
    const double other =
        FramePsnr(video, k, Input("moving.lfv"), fmt::format("{} --frame {}", kWide, (k + 1) % 3));
    EXPECT_GT(own, other + 3.0) << k;
  }
  // From --frame 1, two frames, with a sweep across them.
  const auto part =
      Lfcam(fmt::format("render {} --frame 1 --frames 2 --size 96x64 --aperture "
                        "60:120 --video {}",
                        Input("moving.lfv"), Path("part.mp4")));
  ASSERT_EQ(part.status, 0) << part.output;
  EXPECT_EQ(testing::DecodeMp4(Path("part.mp4")).frames.size(), 2u);
}

TEST_F(RenderVideoCli, NonsenseIsRefusedNamingTheFlagOrFileAndNothingIsWritten) {
  const std::string still = Input("still.lf"), out = Path("bad.mp4");
  std::ofstream(Path("broken.json")) << R"({"format": "lfcam-view", "version": 1, "camera": {}})";
  std::ofstream(Path("wide.json"))
      << R"({"format": "lfcam-view", "version": 1, "camera": {"width": 128, "height": 64,
      "eye": [300, 270, 3600], "look_at": [300, 270, -700], "up": [0, 1, 0], "focal_length_mm": 600,
      "focus_distance_mm": 4000, "aperture_mm": 0, "lens_rate": 4, "breathing": true}})";
  std::ofstream(Path("narrow.json"))
      << R"({"format": "lfcam-view", "version": 1, "camera": {"width": 64, "height": 64,
      "eye": [300, 270, 3600], "look_at": [300, 270, -700], "up": [0, 1, 0], "focal_length_mm": 600,
      "focus_distance_mm": 4000, "aperture_mm": 0, "lens_rate": 4, "breathing": true}})";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--focus-distance 3400:5200 --size 63x64 --video " + out, "63x64 video"},
      {"--focus-distance 3400:5200 --video " + Path("bad.avi"), "must end in .mp4"},
      {"--video " + out, "nothing changes"},
      {"--focus-distance 3400:5200 --out " + Path("x.png"), "goes with --video"},
      {"--frames 10 --out " + Path("x.png"), "--frames: goes with --video"},
      {"--focus-distance 3400:300 --video " + out, "--focus-distance: 300 must exceed"},
      {"--focus-distance 3400:abc --video " + out, "--focus-distance"},
      {"--eye 1,2,3:4,5 --video " + out, "--eye"},
      {"--up 0,1,0:1,0,0 --video " + out, "not for --up"},
      {"--path " + Path("wide.json") + " --video " + out, "two views or more"},
      {"--path " + Path("wide.json") + "," + Path("broken.json") + " --video " + out,
       "broken.json"},
      {"--path " + Path("wide.json") + "," + Path("narrow.json") + " --video " + out,
       "narrow.json: camera.width/height 64x64"},
      {"--path " + Path("wide.json") + "," + Path("narrow.json") + " --aperture 10:20 --video " +
           out,
       "not with a range"},
      {"--aperture 10:20 --video " + out + " --out " + Path("x.png"), "excludes"},
      {"--aperture 10:20 --hit-mask " + Path("m.png") + " --video " + out, "--hit-mask"},
  };
  for (const auto& [flags, expected] : cases) {
    const auto run = Lfcam(fmt::format("render {} {}", still, flags));
    EXPECT_EQ(run.status, 2) << flags << "\n" << run.output;
    EXPECT_NE(run.output.find(expected), std::string::npos) << flags << "\n" << run.output;
  }
  const auto too_many =
      Lfcam(fmt::format("render {} --frames 5 --video {}", Input("moving.lfv"), out));
  EXPECT_EQ(too_many.status, 2) << too_many.output;
  EXPECT_NE(too_many.output.find("--frames 5: "), std::string::npos) << too_many.output;
  EXPECT_NE(too_many.output.find("has 3 frames from --frame 0"), std::string::npos);
  for (const char* name : {"bad.mp4", "bad.avi", "x.png", "m.png"})
    EXPECT_FALSE(fs::exists(Path(name))) << name;
  for (const auto& entry : fs::directory_iterator(*dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace lfcam
