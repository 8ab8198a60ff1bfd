#pragma once
// Each module's photometric response (the paper leaves its modules' brightness and white
// balance inconsistent): what a module records of linear radiance L is modelled as
//   gain[c] * (1 + vignetting * rho^2) * L,
// rho the distance from the principal point over the image's half-diagonal. The world shot
// shows every camera the same board at the st-plane (no parallax), so the modules are compared
// on it, square by square, and the model is fitted jointly: each square's radiance is the
// median over the cameras of what they saw, corrected by the current estimate, and each
// camera's gain and vignetting are refitted against those radiances. Gains are normalised so
// that the array's median camera keeps its colour.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "lfcam/calib/calibration_file.h"
#include "lfcam/session/board.h"
#include "lfcam/session/session.h"

namespace lfcam {

struct PhotometryEstimate {
  std::vector<std::optional<PhotometricCorrection>> cameras;  // row-major; none where unseen
  int squares = 0;                                            // board squares compared
};

// Reads the world shot (decoded at reduced size) and fits the model for every calibrated camera
// that saw the world board. `image_done` is called once per image.
PhotometryEstimate EstimatePhotometry(const std::filesystem::path& session_dir,
                                      const CaptureManifest& manifest,
                                      const CalibrationFile& calibration,
                                      const BoardSpec& world_board,
                                      const std::function<void()>& image_done = {});

// Records the estimate in a calibration.json document: "photometry" on each camera it covers,
// and a top-level "photometry" summary.
void AddPhotometryToCalibration(nlohmann::json& calibration, const PhotometryEstimate& estimate);

}  // namespace lfcam
