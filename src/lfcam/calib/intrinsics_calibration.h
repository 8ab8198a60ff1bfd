#pragma once
// One module's intrinsics and distortion (k1, k2, p1, p2, k3) from its views of a board, with
// OpenCV (cv::calibrateCamera): the paper's per-camera step, and `lfcam calibrate intrinsics`.
#include <opencv2/core.hpp>
#include <vector>

#include "lfcam/core/camera_model.h"
#include "lfcam/session/board.h"

namespace lfcam {

struct SingleCameraCalibration {
  CameraIntrinsics intrinsics;
  std::vector<Rigid3> camera_from_board;  // one per view, in the order given
  std::vector<double> view_rms_px;        // reprojection RMS per view
  double rms_px = 0;                      // over all views
};

// At least 3 views are needed (throws lfcam::Error saying so); `width`, `height` are the images'.
SingleCameraCalibration CalibrateSingleCamera(const std::vector<std::vector<cv::Point2f>>& views,
                                              const BoardSpec& board, int width, int height);

// camera_from_board of a board seen by a calibrated camera (cv::solvePnP, iterative).
Rigid3 BoardPose(const CameraIntrinsics& intrinsics, const BoardSpec& board,
                 const std::vector<cv::Point2f>& corners);

}  // namespace lfcam
