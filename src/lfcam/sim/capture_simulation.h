#pragma once
// A raw capture session played by the simulator: every module of the array photographs the
// intrinsics board in several poses, the world board at the view window, and the scene, and the
// session is written in the capture layout (session/session.h) with ground_truth.json beside.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/session/board.h"
#include "lfcam/session/session.h"
#include "lfcam/sim/camera_module.h"
#include "lfcam/sim/scene.h"

namespace lfcam {

// The simulator's intrinsics boards: 30 mm squares, a chessboard of 10 x 7 inner corners, or a
// ChArUco board of 11 x 9 squares (an odd row count: OpenCV 4.6 lays out boards of an even row
// count unlike other versions).
inline constexpr const char* kSimulatedChessboard = "10x7@30";
inline constexpr const char* kSimulatedCharuco = "charuco:11x9@30/22";

struct CaptureSimulationOptions {
  int rows = 10, cols = 10;
  int sensor_width = kPiCameraWidth, sensor_height = kPiCameraHeight;
  ModuleDefects defects = ModuleDefects::kRealistic;
  std::uint64_t seed = 1;
  BoardSpec intrinsics_board{10, 7, 30.0};
  int intrinsics_shots = 14;
  int scene_supersampling = 2;  // per axis: the scene shot, and what the boards stand before
  bool noise = true;            // false: an ideal sensor (tests)
  // Every module's lens blur, a Gaussian point spread of this sigma on the sensor (um; 0: a
  // perfect lens), in place of what `defects` draws (MakeModules).
  std::optional<double> lens_blur_um;
  // The world board hung the other way up: turned 180 degrees in its plane about its centre (its
  // bottom-left square, seen from the array, is white). The world frame stays where it was.
  bool world_board_turned = false;
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

// The simulated array and its shots: the modules (with their defects), the intrinsics board's
// poses, and for every shot what each module records. SimulateCapture photographs every shot
// with every module; a simulated node (node/simulated_camera.h) photographs them with one.
class SimulatedArray {
 public:
  struct ShotPlan {
    ShotKind kind;
    std::string name, dir;  // "shot_03", "calib/intrinsics/shot_03"
    // What stands before the scene (a board), or empty: the scene alone.
    PixelRadiance radiance;
    // Where `radiance` may differ from the scene (empty: everywhere).
    std::function<PixelRuns(const SimulatedModule&, const cv::Mat& directions)> runs;
  };
  // What a module computes once and shares between its shots: its rays, and the scene's
  // radiance (supersampled), which the scene shot records and the boards stand before.
  struct ModuleCache {
    cv::Mat directions, scene;
  };

  // `scene` must outlive the array.
  SimulatedArray(const Scene& scene, const CaptureSimulationOptions& options);

  const ArrayPlane& array() const { return array_; }
  const BoardSpec& world_board() const { return world_board_; }
  const std::vector<SimulatedModule>& modules() const { return modules_; }
  const std::vector<Rigid3>& intrinsics_board_poses() const { return board_poses_; }
  const std::vector<ShotPlan>& shots() const { return plans_; }
  // Where the world board stands: the identity (the world frame is the board's), or turned.
  Rigid3 world_from_world_board() const;
  // Indices, or nullopt when there is no such module or shot.
  std::optional<std::size_t> module_at(int row, int col) const;
  std::optional<std::size_t> shot_named(const std::string& name) const;

  // What module `module` records in shot `shot` (8-bit sRGB RGB), deterministic in the seed.
  cv::Mat Expose(std::size_t module, std::size_t shot, ModuleCache& cache) const;
  // A video frame: what module `module` records of the scene at time t (Scene::AtTime; an
  // instant's exposure: no motion blur, no rolling shutter), its noise drawn for frame number
  // `frame`. Only the pixels that may see something that moves are traced again; the rest are
  // the still scene's, which `cache` keeps.
  cv::Mat ExposeAt(std::size_t module, double t_seconds, std::uint64_t frame,
                   ModuleCache& cache) const;

 private:
  const Scene& scene_;
  CaptureSimulationOptions options_;
  ArrayPlane array_;
  BoardSpec world_board_;
  std::vector<SimulatedModule> modules_;
  std::vector<Rigid3> board_poses_;
  std::vector<ShotPlan> plans_;
};

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
