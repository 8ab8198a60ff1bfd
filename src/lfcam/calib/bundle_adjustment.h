#pragma once
// Joint array calibration: one bundle adjustment (Ceres Solver) over every camera's intrinsics,
// distortion and pose and every intrinsics-board pose, with a robust loss. The world board's
// corners are observations too, with its pose held at the identity: it defines the world frame,
// so the adjusted rig comes out placed in it.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "lfcam/calib/session_detection.h"
#include "lfcam/core/camera_model.h"
#include "lfcam/session/board.h"

namespace lfcam {

struct RigCamera {
  int row = 0, col = 0;
  CameraIntrinsics intrinsics;
  Rigid3 camera_from_world;
  const std::vector<BoardView>* views = nullptr;                   // intrinsics board detections
  const std::optional<std::vector<cv::Point2f>>* world = nullptr;  // world board detection
  double rms_px = 0;  // reprojection RMS over its corners, after adjustment
  int corners = 0;
};

struct BundleAdjustmentOptions {
  double huber_px = 1.0;  // residuals beyond this count linearly, not quadratically
  int max_iterations = 100;
  int threads = 0;  // 0: all cores
};

struct BundleAdjustmentReport {
  int residual_blocks = 0, parameters = 0, iterations = 0;
  double initial_rms_px = 0, final_rms_px = 0;
  double seconds = 0;
  bool converged = false;
  std::string summary;  // Ceres' one-line report
};

// Adjusts `cameras` and `world_from_board` (one per intrinsics shot; shots with
// `shot_known[k]` false are left out) in place.
BundleAdjustmentReport BundleAdjustArray(std::vector<RigCamera>& cameras,
                                         std::vector<Rigid3>& world_from_board,
                                         const std::vector<bool>& shot_known,
                                         const BoardSpec& intrinsics_board,
                                         const BoardSpec& world_board,
                                         const BundleAdjustmentOptions& options = {});

// The reprojection error of one camera over the given board corners (RMS, px).
double ReprojectionRms(const CameraIntrinsics& intrinsics, const Rigid3& camera_from_board,
                       const std::vector<Vec3>& board_points,
                       const std::vector<cv::Point2f>& corners);

}  // namespace lfcam
