#pragma once
// Reading calibration.json back (docs/calibration.md): what `lfcam build` needs of it.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/camera_model.h"
#include "lfcam/core/slab.h"

namespace lfcam {

// A module's photometric response (calib/photometry.h): it records
// gain[c] * falloff(x, y) * L of linear radiance L.
struct PhotometricCorrection {
  Vec3 gain = Vec3::Ones();
  double vignetting = 0;  // falloff = 1 + vignetting * rho^2
  double rho_max = 0;     // the largest rho the estimate saw: beyond it, extrapolated

  // rho: the distance from the principal point over the image's half-diagonal.
  double falloff(const CameraIntrinsics& k, double x, double y) const;
  // The falloff's growth per squared pixel of distance from the principal point: falloff =
  // 1 + per_pixel2 * (dx^2 + dy^2), for loops that hoist the row's term.
  double falloff_per_pixel2(const CameraIntrinsics& k) const;
};
nlohmann::json PhotometryToJson(const PhotometricCorrection& p);
PhotometricCorrection PhotometryFromJson(const nlohmann::json& j, const std::string& where);

struct CalibratedCamera {
  int row = 0, col = 0;
  bool calibrated = false;
  std::string reason;  // when not
  CameraIntrinsics intrinsics;
  Rigid3 world_from_camera;
  std::optional<PhotometricCorrection> photometry;
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

// The calibration of the same cameras in another sensor mode of the same field of view (a
// video's binned mode: 648x486 or 1296x972 of a 2592x1944 calibration): focal lengths and
// principal points scaled, pixel centres kept where they are; the distortion, the poses and the
// photometry (in units of the image's half-diagonal) are unchanged. Throws lfcam::Error when the
// mode's aspect ratio is not the calibration's.
CalibrationFile ScaledCalibration(const CalibrationFile& calibration, int width, int height);

}  // namespace lfcam
