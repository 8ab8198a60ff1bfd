#include "lfcam/viewer/video_playback.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <thread>

#include "lfcam/cli/share_test_support.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using Clock = VideoPlayback::Clock;
using std::chrono::milliseconds;

class VideoPlaybackTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // moving.lfv: 3 frames at 2 fps; still.lf (shared by every test process).
    dir_ = new fs::path(testing::SharedSharingLightFields());
  }
  static void TearDownTestSuite() { delete dir_; }
  // Ticks at `at` until the frame shown is `k` (the decoder runs on its own thread).
  static bool ShowsWithin(VideoPlayback& p, std::int64_t k, Clock::time_point at) {
    for (int i = 0; i < 500; ++i) {
      p.Tick(at);
      if (p.current_index() == k) return true;
      std::this_thread::sleep_for(milliseconds(10));
    }
    return false;
  }
  static bool SameSamples(const LightField& a, const LightField& b) {
    return a.total_bytes() == b.total_bytes() &&
           std::memcmp(a.data(), b.data(), a.total_bytes()) == 0;
  }
  static inline fs::path* dir_ = nullptr;
};

TEST_F(VideoPlaybackTest, PlaysAtTheVideosRateAndLoops) {
  VideoPlayback p(*dir_ / "moving.lfv");
  ASSERT_TRUE(p.is_video());
  EXPECT_EQ(p.frames(), 3);
  EXPECT_EQ(p.fps(), 2.0);
  EXPECT_FALSE(p.playing());
  const Clock::time_point t0 = Clock::now();
  p.Play(t0);
  EXPECT_FALSE(p.Tick(t0 + milliseconds(400))) << "frame 0 lasts half a second";
  EXPECT_TRUE(ShowsWithin(p, 1, t0 + milliseconds(600)));
  EXPECT_TRUE(ShowsWithin(p, 2, t0 + milliseconds(1100)));
  EXPECT_TRUE(ShowsWithin(p, 0, t0 + milliseconds(1600))) << "looped";
  EXPECT_TRUE(p.playing());
  // Each frame shown is the file's frame.
  const LightFieldVideo file(*dir_ / "moving.lfv");
  ASSERT_TRUE(ShowsWithin(p, 1, t0 + milliseconds(2100)));
  EXPECT_TRUE(SameSamples(*p.current(), file.ReadFrame(1)));
  EXPECT_FALSE(SameSamples(*p.current(), file.ReadFrame(2)));
}

TEST_F(VideoPlaybackTest, StopsAtTheEndWithoutLoopAndCountsWhatItSkips) {
  VideoPlayback p(*dir_ / "moving.lfv");
  p.set_loop(false);
  // The decoder reads ahead of the playhead: frames 1 and 2 are ready before long.
  for (int i = 0; i < 500 && !(p.ready(1) && p.ready(2)); ++i)
    std::this_thread::sleep_for(milliseconds(10));
  ASSERT_TRUE(p.ready(1) && p.ready(2));
  const Clock::time_point t0 = Clock::now();
  p.Play(t0);
  // The clock jumps past frame 1: it is never shown, and counted.
  EXPECT_TRUE(ShowsWithin(p, 2, t0 + milliseconds(1100)));
  EXPECT_EQ(p.skipped(), 1);
  p.Tick(t0 + milliseconds(9000));
  EXPECT_FALSE(p.playing()) << "the end, without loop";
  EXPECT_EQ(p.current_index(), 2);
  p.Play(t0 + milliseconds(9000));  // from the start again
  EXPECT_EQ(p.playhead(), 0);
}

TEST_F(VideoPlaybackTest, SeeksAndStepsShowTheFrameAskedFor) {
  VideoPlayback p(*dir_ / "moving.lfv");
  p.Seek(2);
  EXPECT_TRUE(p.Tick());
  EXPECT_EQ(p.current_index(), 2);
  p.Step(-1);
  p.Tick();
  EXPECT_EQ(p.current_index(), 1);
  p.Step(-2);  // looping: from 1 back past 0 to 2
  p.Tick();
  EXPECT_EQ(p.current_index(), 2);
  p.set_loop(false);
  p.Step(5);
  p.Tick();
  EXPECT_EQ(p.current_index(), 2) << "clamped without loop";
  p.Play();
  p.Step(-1);
  EXPECT_FALSE(p.playing()) << "a step pauses";
  p.Seek(-4);
  p.Tick();
  EXPECT_EQ(p.current_index(), 0);
  EXPECT_GT(p.decode_ms(), 0.0);
  EXPECT_TRUE(p.error().empty());
}

TEST_F(VideoPlaybackTest, AStillIsAVideoOfOneFrameAndAMissingFrameIsNamed) {
  VideoPlayback still(*dir_ / "still.lf");
  EXPECT_FALSE(still.is_video());
  EXPECT_EQ(still.frames(), 1);
  still.Play();
  EXPECT_FALSE(still.playing());
  EXPECT_FALSE(still.Tick());
  EXPECT_NE(testing::ErrorOf([&] {
              VideoPlayback(*dir_ / "moving.lfv", 7);
            }).find("there is no frame 7 (3 frames)"),
            std::string::npos);
}

}  // namespace
}  // namespace lfcam
