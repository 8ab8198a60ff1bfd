#pragma once
// Calibrating a whole array from a capture session (docs/calibration.md):
//   1. every board found (calib/session_detection.h);
//   2. each camera alone: intrinsics and distortion (OpenCV), its pose against the world board;
//      this is the paper's method, kept for comparison;
//   3. joint: one bundle adjustment over all cameras and board poses (calib/bundle_adjustment.h);
//   4. the paper's array fit on the jointly estimated centres: plane, grid, PRP window.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/calib/array_fit.h"
#include "lfcam/calib/bundle_adjustment.h"
#include "lfcam/core/slab.h"
#include "lfcam/session/board.h"
#include "lfcam/session/session.h"

namespace lfcam {

inline constexpr int kCalibrationVersion = 1;

struct CameraCalibration {
  int row = 0, col = 0;
  bool calibrated = false;
  std::string reason;  // why not, when not
  CameraIntrinsics intrinsics;
  Rigid3 world_from_camera;
  double rms_px = 0;
  int corners = 0;
  std::vector<std::string> shots_used;  // intrinsics shots whose board it found
  bool world_board_found = false;
  Vec3 ideal_center = Vec3::Zero();
  double distance_to_ideal_mm = 0;
  std::vector<std::string> warnings;
  // The paper's method, for comparison: this camera calibrated alone, placed by the world board.
  std::optional<CameraIntrinsics> single_intrinsics;
  std::optional<Vec3> single_center;
  double single_rms_px = 0;
};

struct CalibrationOptions {
  std::optional<BoardSpec> intrinsics_board, world_board;  // default: the manifest's
  int min_views = 4;                 // intrinsics shots a camera must see the whole board in
  std::function<void()> image_done;  // once per image searched
};

struct ArrayCalibration {
  int rows = 0, cols = 0;
  double pitch_mm = 0;
  int width = 0, height = 0;
  BoardSpec intrinsics_board, world_board;
  std::vector<std::string> intrinsics_shots;
  std::vector<CameraCalibration> cameras;  // row-major, every grid position
  std::vector<Rigid3> world_from_board;    // per intrinsics shot (adjusted)
  BundleAdjustmentReport bundle_adjustment;
  ArrayFit fit;                        // on the joint centres
  std::optional<ArrayFit> single_fit;  // the paper's method, on the per-camera centres
  Slab slab;                           // PRP window + view window (the world board)
  // The world board was hung the other way up (its bottom-left square, seen from the array,
  // white): its corners were numbered from the other end, and the world frame turned back.
  bool world_board_turned = false;
  double detection_seconds = 0, seconds = 0;

  const CameraCalibration& camera(int row, int col) const {
    return cameras[std::size_t(row * cols + col)];
  }
  int calibrated_count() const;
};

ArrayCalibration CalibrateArray(const std::filesystem::path& session_dir,
                                const CaptureManifest& manifest, const CalibrationOptions& options);

nlohmann::json CalibrationToJson(const ArrayCalibration& calibration);

}  // namespace lfcam
