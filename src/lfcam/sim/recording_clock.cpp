#include "lfcam/sim/recording_clock.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "lfcam/core/error.h"

namespace lfcam {

std::vector<RecordedFrame> SimulateNodeFrames(int node, double duration_s,
                                              const RecordingClockOptions& o) {
  if (!(o.fps > 0 && o.fps <= 1000) || !(duration_s >= 0 && duration_s <= 86400) || node < 0)
    throw Error("recording clock: fps in (0, 1000], a duration of 0 to 86400 s and a node >= 0");
  std::mt19937_64 rng(o.seed * 1000003ULL + std::uint64_t(node));
  const auto uniform = [&](double half) {
    return std::uniform_real_distribution<double>(-half, half)(rng);
  };
  std::normal_distribution<double> jitter(0.0, o.period_jitter_s);
  std::bernoulli_distribution dropped(std::clamp(o.drop_rate, 0.0, 1.0));
  const double period = 1.0 / o.fps;
  // The node's clocks: its wall clock's offset from true time (chrony keeps its rate), and its
  // sensor crystal's rate error.
  const double offset = uniform(o.clock_offset_s);
  const double drift = uniform(o.clock_drift_ppm) * 1e-6;
  const double boot = 100.0 + 10.0 * std::uniform_real_distribution<double>(0, 1)(rng);
  // Free-running, the first frame starts at any phase.
  double start = o.sync ? 0.0 : std::uniform_real_distribution<double>(0, period)(rng);
  std::vector<RecordedFrame> frames;
  for (int sequence = 0;; ++sequence) {
    double t, wall;
    if (o.sync) {
      // Sync steers each frame's wall-clock start onto the server's grid, to within its error
      // (the server's own frames are the grid); the true start is off by the node's clock.
      wall = sequence * period + (node == 0 ? 0.0 : uniform(o.sync_error_s));
      t = wall - offset;
    } else {
      // Free-running: the crystal's period, each jittered.
      t = start;
      wall = t + offset;
      start += period * (1.0 + drift) + jitter(rng);
    }
    // With sync a frame belongs to the recording by its slot on the grid (its start may fall a
    // few microseconds before 0); free-running, by its start.
    if ((o.sync ? sequence * period : t) >= duration_s) break;
    if (dropped(rng)) continue;
    RecordedFrame f;
    f.sequence = sequence;
    f.exposure_start = t;
    f.wall_clock = wall;
    f.sensor_timestamp = boot + t * (1.0 + drift);
    frames.push_back(f);
  }
  return frames;
}

double ExposureSpread(const std::vector<const RecordedFrame*>& frames) {
  if (frames.empty()) return 0.0;
  double lo = frames.front()->exposure_start, hi = lo;
  for (const RecordedFrame* f : frames) {
    lo = std::min(lo, f->exposure_start);
    hi = std::max(hi, f->exposure_start);
  }
  return hi - lo;
}

}  // namespace lfcam
