#pragma once
// When a simulated node's camera exposes its video frames, and what its clocks say of them
// (issue 24: light field video; ../shared/DESIGN.md, "Light field video"). What real multi-Pi rigs
// show: each Pi's wall clock is off from true time by what chrony leaves (tens of microseconds
// to a server on the same wired LAN, milliseconds over Wi-Fi or the Internet); its sensor runs
// off its own crystal, a little fast or slow (tens of ppm), and libcamera maps each frame's
// sensor time to the wall clock; frame periods jitter; a frame is dropped now and then. Without
// libcamera's software sync the nodes start at unrelated phases and run at their crystals'
// rates; with it (`rpicam-vid --sync`) each client steers its frames so that their wall-clock
// times land within tens of microseconds of the server's: the frames line up on the nodes'
// wall clocks, so their true exposures differ by that plus the clocks' own disagreement, which
// no timestamp shows.
//
// Times are seconds. `true` time is the simulator's (the scene's t, Scene::AtTime); a frame's
// wall-clock time is its exposure start on the node's own clock (libcamera's FrameWallClock), its
// sensor timestamp the same on the sensor's monotonic clock (SensorTimestamp), from the node's
// boot.
#include <cstdint>
#include <vector>

namespace lfcam {

struct RecordingClockOptions {
  double fps = 30.0;
  bool sync = true;               // libcamera's software sync, one node the server
  double sync_error_s = 30e-6;    // with sync: a frame's wall-clock start against the server's (±)
  double clock_offset_s = 20e-6;  // each node's wall clock against true time (±, uniform)
  double clock_drift_ppm = 20.0;  // each node's sensor crystal against true time (±, uniform)
  double period_jitter_s = 50e-6;  // free-running: a frame period's jitter (Gaussian sigma)
  double drop_rate = 0.002;        // a frame's chance of being dropped
  std::uint64_t seed = 1;
};

struct RecordedFrame {
  int sequence = 0;             // the node's frame number (a dropped frame's number is skipped)
  double exposure_start = 0;    // true time
  double wall_clock = 0;        // the node's wall clock then (what it reports)
  double sensor_timestamp = 0;  // the sensor clock then
};

// The frames node `node` (0 is the sync server) records over [0, duration_s) of true time, in
// order: free-running, those whose exposures start then; with sync, those of the frame slots
// (period apart from 0 on the wall clock) then, each wall-clock start within the sync error of
// its slot. Deterministic in (options.seed, node).
std::vector<RecordedFrame> SimulateNodeFrames(int node, double duration_s,
                                              const RecordingClockOptions& options);

// The spread of a set of frames' true exposure starts (latest minus earliest): the sync error of
// a light field frame made of them.
double ExposureSpread(const std::vector<const RecordedFrame*>& frames);

}  // namespace lfcam
