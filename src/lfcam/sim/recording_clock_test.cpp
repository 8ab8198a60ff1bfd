#include "lfcam/sim/recording_clock.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

// The frames of `nodes` nodes over `seconds`, by node.
std::vector<std::vector<RecordedFrame>> Record(int nodes, double seconds,
                                               const RecordingClockOptions& o) {
  std::vector<std::vector<RecordedFrame>> out;
  for (int n = 0; n < nodes; ++n) out.push_back(SimulateNodeFrames(n, seconds, o));
  return out;
}

// Each frame number's spread of true exposure starts over the nodes that have it.
std::vector<double> SpreadsBySequence(const std::vector<std::vector<RecordedFrame>>& nodes) {
  std::map<int, std::vector<const RecordedFrame*>> by_sequence;
  for (const auto& frames : nodes)
    for (const RecordedFrame& f : frames) by_sequence[f.sequence].push_back(&f);
  std::vector<double> spreads;
  for (const auto& [sequence, frames] : by_sequence) spreads.push_back(ExposureSpread(frames));
  return spreads;
}

TEST(RecordingClock, WithSyncEveryFrameStartsWithinTheSyncError) {
  RecordingClockOptions o;
  o.drop_rate = 0;
  const auto nodes = Record(100, 2.0, o);
  for (const auto& frames : nodes) ASSERT_EQ(frames.size(), 60u);  // 30 fps for 2 s
  const std::vector<double> spreads = SpreadsBySequence(nodes);
  ASSERT_EQ(spreads.size(), 60u);
  // Their true starts are off by the sync error and the two clocks' offsets.
  for (const double s : spreads) EXPECT_LE(s, 2 * (o.sync_error_s + o.clock_offset_s) + 1e-12);
  // ... and a frame period apart, frame after frame.
  for (std::size_t k = 1; k < nodes[7].size(); ++k)
    EXPECT_NEAR(nodes[7][k].exposure_start - nodes[7][k - 1].exposure_start, 1.0 / 30,
                2 * o.sync_error_s);
  // What the wall clocks say differs from the truth by no more than the clocks' offsets.
  for (std::size_t k = 0; k < 60; ++k) {
    double lo = 1e9, hi = -1e9;
    for (const auto& frames : nodes) {
      lo = std::min(lo, frames[k].wall_clock);
      hi = std::max(hi, frames[k].wall_clock);
    }
    EXPECT_LE(hi - lo, 2 * o.sync_error_s + 1e-12);
    EXPECT_NEAR(hi - lo, spreads[k], 2 * o.clock_offset_s);
  }
}

TEST(RecordingClock, WithoutSyncTheNodesDriftApart) {
  RecordingClockOptions o;
  o.sync = false;
  o.drop_rate = 0;
  const std::vector<double> spreads = SpreadsBySequence(Record(100, 2.0, o));
  std::vector<double> sorted = spreads;
  std::sort(sorted.begin(), sorted.end());
  // 100 nodes at unrelated phases: the median frame spans most of a period (33 ms).
  EXPECT_GT(sorted[sorted.size() / 2], 0.8 / 30);
}

TEST(RecordingClock, ClocksAreOffAndDriftWithinTheirBoundsAndFramesDrop) {
  RecordingClockOptions o;
  o.drop_rate = 0.05;
  const auto nodes = Record(20, 10.0, o);
  std::size_t frames = 0, gaps = 0;
  for (const auto& node : nodes) {
    frames += node.size();
    for (std::size_t k = 0; k < node.size(); ++k) {
      const RecordedFrame& f = node[k];
      const double t = f.exposure_start;
      // The wall clock's error: its offset.
      EXPECT_LE(std::abs(f.wall_clock - t), o.clock_offset_s + 1e-12);
      if (k > 0) {
        EXPECT_GT(f.sequence, node[k - 1].sequence);
        gaps += std::size_t(f.sequence - node[k - 1].sequence - 1);
        // The sensor clock runs on from boot at the node's rate.
        const double dt = f.exposure_start - node[k - 1].exposure_start;
        EXPECT_NEAR(f.sensor_timestamp - node[k - 1].sensor_timestamp, dt, 20e-6 * dt + 1e-9);
      }
    }
  }
  // 20 nodes x 300 frames, 5% dropped: about 300 gone (a binomial's spread is about 17).
  EXPECT_NEAR(double(6000 - frames), 300.0, 80.0);
  EXPECT_GT(gaps, 200u);
  // The same seed and node: the same frames; another node: another clock.
  EXPECT_EQ(SimulateNodeFrames(3, 10.0, o).size(), nodes[3].size());
  EXPECT_NE(nodes[3][0].wall_clock, nodes[4][0].wall_clock);
  EXPECT_THROW(SimulateNodeFrames(0, 1.0, RecordingClockOptions{0.0}), Error);
}

}  // namespace
}  // namespace lfcam
