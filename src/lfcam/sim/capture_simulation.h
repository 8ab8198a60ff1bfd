#pragma once
// A raw capture session played by the simulator: every module of the array photographs the
// intrinsics board in several poses, the world board at the view window, and the scene, and the
// session is written in the capture layout (capture/session.h) with ground_truth.json beside.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lfcam/calib/board.h"
#include "lfcam/sim/camera_module.h"
#include "lfcam/sim/scene.h"

namespace lfcam {

struct CaptureSimulationOptions {
  int rows = 10, cols = 10;
  int sensor_width = kPiCameraWidth, sensor_height = kPiCameraHeight;
  ModuleDefects defects = ModuleDefects::kRealistic;
  std::uint64_t seed = 1;
  BoardSpec intrinsics_board{10, 7, 30.0};
  int intrinsics_shots = 14;
  int scene_supersampling = 2;       // per axis, for the scene shot
  bool noise = true;                 // false: an ideal sensor (tests)
  std::function<void()> image_done;  // called once per image written (any thread, serialised)
};

// The intrinsics board's poses: in front of the array at about one to one and a half times the
// distance where it fills 40% of a module's width, tilted up to 25 degrees, some off-centre so
// that the board reaches the corners of some cameras' images. Deterministic in `seed`.
std::vector<Rigid3> IntrinsicsBoardPoses(const ArrayPlane& array, const BoardSpec& board, int count,
                                         std::uint64_t seed);

// Whether `module` sees the whole board with its white margin (every outer corner in the image).
bool SeesWholeBoard(const SimulatedModule& module, const BoardSpec& board,
                    const Rigid3& world_from_board, double margin_squares = 1.0);

struct CaptureSimulationResult {
  std::size_t images = 0;
  double seconds = 0;
};

// Writes the session into `out_dir`, which must not exist or be empty: everything is written
// into a sibling "NAME.partial-PID" directory that is renamed into place at the end, so a failed
// or interrupted run leaves no half-written session under the name.
CaptureSimulationResult SimulateCapture(const Scene& scene, const CaptureSimulationOptions& options,
                                        const std::filesystem::path& out_dir);

}  // namespace lfcam
