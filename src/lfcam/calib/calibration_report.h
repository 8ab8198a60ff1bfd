#pragma once
// The calibration at a glance: two maps of the array, as seen from behind it (row 0 at the
// bottom), one cell per camera: the reprojection error and the distance of the measured centre
// from its ideal grid position. The worst cameras are labelled; cameras that could not be
// calibrated are crossed out.
#include <opencv2/core.hpp>

#include "lfcam/calib/array_calibration.h"

namespace lfcam {

// An 8-bit RGB picture (CV_8UC3).
cv::Mat DrawCalibrationReport(const ArrayCalibration& calibration);

}  // namespace lfcam
