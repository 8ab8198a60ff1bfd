// Light field frames from a simulated recording (session/frame_alignment.h against what the
// simulator knows, sim/recording_clock.h): the spread the clocks report against the true one,
// and every frame a camera lost named.
#include "lfcam/session/frame_alignment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/sim/recording_clock.h"

namespace lfcam {
namespace {

constexpr std::int64_t kStart = 1'800'000'000'000'000'000;

struct Recording {
  Shot shot;
  std::vector<std::vector<RecordedFrame>> truth;  // per camera, row-major
};

// What `rows` x `cols` simulated nodes record (camera 0 the sync server), as a video shot.
Recording Record(int rows, int cols, double seconds, const RecordingClockOptions& o) {
  Recording r;
  r.shot.kind = ShotKind::kVideo;
  r.shot.name = "rec_00";
  r.shot.video = VideoShot{o.fps, seconds, 64, 48, o.sync ? "on" : "off", kStart, 1};
  for (int c = 0; c < rows * cols; ++c) {
    r.truth.push_back(SimulateNodeFrames(c, seconds, o));
    ShotImage image(c / cols, c % cols, "video/rec_00/x.mjpeg");
    std::uint64_t offset = 0;
    for (const RecordedFrame& f : r.truth.back()) {
      image.frames.push_back({f.sequence, offset, 1000, kStart + std::llround(f.wall_clock * 1e9),
                              std::llround(f.sensor_timestamp * 1e9)});
      offset += 1000;
    }
    r.shot.images.push_back(std::move(image));
  }
  return r;
}

// The true spread of each light field frame: its frames' true exposure starts.
std::vector<std::optional<double>> TrueSpreads(const Recording& r, const FrameAlignment& a) {
  std::vector<std::optional<double>> out;
  for (const LightFieldFrame& frame : a.frames) {
    std::vector<const RecordedFrame*> chosen;
    for (std::size_t c = 0; c < frame.frame_of_camera.size(); ++c)
      if (frame.frame_of_camera[c] >= 0)
        chosen.push_back(&r.truth[c][std::size_t(frame.frame_of_camera[c])]);
    out.push_back(chosen.size() >= 2 ? std::optional(ExposureSpread(chosen)) : std::nullopt);
  }
  return out;
}

TEST(FrameAlignment, WithSyncEveryFramesSpreadIsTheTruthsWithinATenthOfAMillisecond) {
  RecordingClockOptions o;  // sync, 30 fps, the defaults' drops and clocks
  const Recording r = Record(10, 10, 10.0, o);
  const FrameAlignment a = AlignFrames(r.shot, 10, 10);
  ASSERT_EQ(a.frames.size(), 300u);
  EXPECT_TRUE(a.problems.empty()) << a.problems.front();
  const auto truth = TrueSpreads(r, a);
  double worst = 0;
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    ASSERT_TRUE(a.frames[k].spread_ns && truth[k]);
    worst = std::max(worst, std::abs(double(*a.frames[k].spread_ns) * 1e-9 - *truth[k]));
  }
  EXPECT_LT(worst, 0.1e-3);
  // Frames lost to alignment: none. Every frame a camera dropped is named missing, and no other.
  for (const CameraSync& s : a.cameras) {
    EXPECT_EQ(s.missing, s.dropped + (300 - s.dropped - s.recorded)) << s.row << "," << s.col;
    EXPECT_EQ(s.recorded + s.missing, 300);
    EXPECT_EQ(s.duplicates, 0);
    EXPECT_EQ(s.outside, 0);
  }
  const SpreadSummary summary = SummarizeSpread(a);
  EXPECT_EQ(summary.frames, 300);
  EXPECT_LT(summary.max_us, 2 * o.sync_error_s * 1e6 + 1);
}

TEST(FrameAlignment, FreeRunningCamerasAreStillGroupedAndTheirSpreadIsReported) {
  RecordingClockOptions o;
  o.sync = false;
  o.drop_rate = 0;
  const Recording r = Record(4, 4, 5.0, o);
  const FrameAlignment a = AlignFrames(r.shot, 4, 4);
  std::int64_t missing = 0;
  for (const CameraSync& s : a.cameras) missing += s.missing + s.duplicates + s.outside;
  // Unrelated phases: each camera's frames still land one per light field frame, except at the
  // two ends, where a camera whose phase is late or early by nearly half a period may miss one.
  EXPECT_LE(missing, 2 * 16);
  const auto truth = TrueSpreads(r, a);
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    if (!a.frames[k].spread_ns || !truth[k]) continue;
    EXPECT_NEAR(double(*a.frames[k].spread_ns) * 1e-9, *truth[k], 0.1e-3);
  }
  // Spreads of most of a period: what no sync costs.
  EXPECT_GT(SummarizeSpread(a).median_us, 0.5e6 / 30);
}

TEST(FrameAlignment, NamesDuplicatesACameraAtAnotherRateAndAClockThatIsOff) {
  RecordingClockOptions o;
  o.drop_rate = 0;
  Recording r = Record(2, 2, 2.0, o);
  std::vector<ShotImage>& cams = r.shot.images;
  // Camera (0, 1) delivers frame 10 twice (a second copy 2 ms later).
  FrameTime copy = cams[1].frames[10];
  copy.wall_clock_ns += 2'000'000;
  cams[1].frames.insert(cams[1].frames.begin() + 11, copy);
  for (std::size_t i = 11; i < cams[1].frames.size(); ++i) ++cams[1].frames[i].sequence;
  // Camera (1, 0) runs at 25 fps.
  for (std::size_t i = 0; i < cams[2].frames.size(); ++i)
    cams[2].frames[i].wall_clock_ns = kStart + std::int64_t(i) * 40'000'000;
  // Camera (1, 1)'s clock is 3 ms fast.
  for (FrameTime& f : cams[3].frames) f.wall_clock_ns += 3'000'000;
  const FrameAlignment a = AlignFrames(r.shot, 2, 2);
  EXPECT_EQ(a.cameras[1].duplicates, 1);
  EXPECT_EQ(a.cameras[1].missing, 0);
  EXPECT_TRUE(a.cameras[2].left_out);
  EXPECT_NE(a.cameras[2].problem.find("25.000 fps"), std::string::npos) << a.cameras[2].problem;
  EXPECT_EQ(a.cameras[2].missing, 60);
  EXPECT_NE(a.cameras[3].problem.find("its clock or its sync is off"), std::string::npos);
  EXPECT_NEAR(a.cameras[3].median_offset_us.value_or(0), 3000, 100);
  ASSERT_EQ(a.problems.size(), 2u);
  EXPECT_EQ(a.frames[10].cameras, 3);
  // The duplicate left out: frame 10 holds the nearer copy.
  EXPECT_EQ(a.frames[10].frame_of_camera[1], 10);
  // A camera not in the shot at all is missing everywhere.
  r.shot.images.pop_back();
  EXPECT_EQ(AlignFrames(r.shot, 2, 2).cameras[3].missing, 60);
}

// High-speed mode: two groups of cameras (a checkerboard), the second's frames half a period
// after the first's. The light field frames come twice as often, each holding one group, each
// group's spread within the sync error; no frame is lost.
TEST(FrameAlignment, StaggeredGroupsInterleaveTheirFrames) {
  RecordingClockOptions o;
  o.drop_rate = 0;
  Recording r = Record(4, 4, 1.0, o);
  r.shot.video->groups = 2;
  const std::int64_t half = 1'000'000'000 / 60;
  for (ShotImage& image : r.shot.images) {
    const int group = (image.row + image.col) % 2;
    image.capture = {{"group", group}};
    for (FrameTime& f : image.frames) f.wall_clock_ns += group * half;
  }
  const FrameAlignment a = AlignFrames(r.shot, 4, 4);
  EXPECT_EQ(a.groups, 2);
  ASSERT_EQ(a.frames.size(), 60u);  // 30 a second from each group
  EXPECT_TRUE(a.problems.empty()) << a.problems.front();
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    const LightFieldFrame& f = a.frames[k];
    EXPECT_EQ(f.group, int(k % 2));
    EXPECT_EQ(f.cameras, 8);
    EXPECT_NEAR(double(f.time_ns - a.frames[0].time_ns), double(k) * double(half), 1e5);
    ASSERT_TRUE(f.spread_ns);
    EXPECT_LE(*f.spread_ns, 60'000 + 1);
    for (std::size_t c = 0; c < 16; ++c)
      EXPECT_EQ(f.frame_of_camera[c] >= 0, a.camera_group[c] == f.group);
  }
  for (const CameraSync& s : a.cameras) {
    EXPECT_EQ(s.missing, 0);
    EXPECT_EQ(s.outside, 0);
  }
}

}  // namespace
}  // namespace lfcam
