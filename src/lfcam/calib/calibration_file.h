#pragma once
// Reading calibration.json back (docs/calibration.md): what `lfcam build` needs of it.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "lfcam/core/camera_model.h"
#include "lfcam/core/slab.h"

namespace lfcam {

struct CalibratedCamera {
  int row = 0, col = 0;
  bool calibrated = false;
  std::string reason;  // when not
  CameraIntrinsics intrinsics;
  Rigid3 world_from_camera;
};

struct CalibrationFile {
  int rows = 0, cols = 0, width = 0, height = 0;
  Slab slab;
  std::vector<CalibratedCamera> cameras;  // row-major, one per grid position
  nlohmann::json summary;                 // array fit and bundle adjustment, for the record

  const CalibratedCamera& camera(int row, int col) const {
    return cameras[std::size_t(row * cols + col)];
  }
};

// Parses a calibration (bounded, exact fields); throws lfcam::Error naming `where` and the field.
CalibrationFile CalibrationFromJson(const nlohmann::json& j, const std::string& where);
CalibrationFile ReadCalibration(const std::filesystem::path& path);

}  // namespace lfcam
