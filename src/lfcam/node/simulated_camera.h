#pragma once
// The `sim` camera of lfcam-node: the simulated Raspberry Pi module at (row, col) of a simulated
// array (sim/capture_simulation.h), photographing the shot the host names ("shot_03", "world",
// "scene") at the resolution and JPEG quality configured. A session shot by nodes of this
// backend holds the same images as `lfcam simulate capture` with the same grid, sensor, seed,
// defects and board. It records video of the scene in motion (Scene::AtTime) with what real
// nodes do to the frames' times (sim/recording_clock.h).
#include <cstdint>
#include <memory>
#include <string>

#include "lfcam/node/camera_backend.h"

namespace lfcam {

struct SimulatedCameraOptions {
  int rows = 10, cols = 10, row = 0, col = 0;
  std::uint64_t seed = 1;
  std::string scene = "paper";
  std::string defects = "realistic";  // or "none"
  std::string board = "chessboard";   // the intrinsics board: chessboard or charuco
  bool noise = true;
  // Video (sim/recording_clock.h): how far this node's wall clock is off (±, microseconds) and
  // its chance of dropping a frame.
  double clock_offset_us = 20;
  double drop_rate = 0.002;
};

// Throws lfcam::Error for a position outside the grid or an unknown scene, defects or board.
std::unique_ptr<CameraBackend> MakeSimulatedCamera(const SimulatedCameraOptions& options);

}  // namespace lfcam
