#include "lfcam/calib/calibration_file.h"

#include <fmt/format.h>

#include <cmath>

#include "lfcam/calib/array_calibration.h"
#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"

namespace lfcam {

double PhotometricCorrection::falloff_per_pixel2(const CameraIntrinsics& k) const {
  const double half_diagonal2 = 0.25 * (double(k.width) * k.width + double(k.height) * k.height);
  return vignetting / half_diagonal2;
}

double PhotometricCorrection::falloff(const CameraIntrinsics& k, double x, double y) const {
  const double dx = x - k.cx, dy = y - k.cy;
  return 1.0 + falloff_per_pixel2(k) * (dx * dx + dy * dy);
}

nlohmann::json PhotometryToJson(const PhotometricCorrection& p) {
  return {{"gain", {p.gain.x(), p.gain.y(), p.gain.z()}},
          {"vignetting", p.vignetting},
          {"rho_max", p.rho_max}};
}

PhotometricCorrection PhotometryFromJson(const nlohmann::json& j, const std::string& where) {
  PhotometricCorrection p;
  p.gain = JsonVec3(j, "gain", where);
  if (!(p.gain.minCoeff() > 0.01 && p.gain.maxCoeff() < 100))
    throw Error(fmt::format("{}: gains must be 0.01..100", where));
  p.vignetting = JsonNumber(j, "vignetting", where);
  if (!(p.vignetting > -0.95 && p.vignetting < 10))
    throw Error(fmt::format("{}: vignetting {} is out of range", where, p.vignetting));
  p.rho_max = JsonNumber(j, "rho_max", where);
  return p;
}

CalibrationFile CalibrationFromJson(const nlohmann::json& j, const std::string& where) {
  JsonFormatVersion(j, "lfcam-calibration", kCalibrationVersion, "calibration", where);
  CalibrationFile c;
  const auto& grid = JsonField(j, "grid", where);
  c.rows = int(JsonInteger(grid, "rows", 1, kMaxViewsPerSide, where + ": grid"));
  c.cols = int(JsonInteger(grid, "cols", 1, kMaxViewsPerSide, where + ": grid"));
  const auto& sensor = JsonField(j, "sensor", where);
  c.width = int(JsonInteger(sensor, "width", 1, kMaxImageSide, where + ": sensor"));
  c.height = int(JsonInteger(sensor, "height", 1, kMaxImageSide, where + ": sensor"));
  try {
    c.slab = JsonField(j, "slab", where).get<Slab>();
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", where, e.what()));
  }
  if (c.slab.uv.rows != c.rows || c.slab.uv.cols != c.cols)
    throw Error(fmt::format("{}: the slab's grid does not match the calibration's", where));
  const auto& cameras = JsonField(j, "cameras", where);
  if (!cameras.is_array() || cameras.size() != std::size_t(c.rows) * std::size_t(c.cols))
    throw Error(
        fmt::format("{}: cameras must list all {}x{} grid positions", where, c.rows, c.cols));
  c.cameras.resize(cameras.size());
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const auto& cj = cameras[i];
    const std::string cw = fmt::format("{}: cameras[{}]", where, i);
    CalibratedCamera cam;
    cam.row = int(JsonInteger(cj, "row", 0, c.rows - 1, cw));
    cam.col = int(JsonInteger(cj, "col", 0, c.cols - 1, cw));
    if (std::size_t(cam.row * c.cols + cam.col) != i)
      throw Error(fmt::format("{}: cameras must be listed row-major", cw));
    const auto& flag = JsonField(cj, "calibrated", cw);
    if (!flag.is_boolean()) throw Error(fmt::format("{}: calibrated must be true or false", cw));
    cam.calibrated = flag.get<bool>();
    if (cam.calibrated) {
      cam.intrinsics = IntrinsicsFromJson(JsonField(cj, "intrinsics", cw), cw + ": intrinsics");
      if (cam.intrinsics.width != c.width || cam.intrinsics.height != c.height)
        throw Error(fmt::format("{}: intrinsics are for {}x{} images, the sensor is {}x{}", cw,
                                cam.intrinsics.width, cam.intrinsics.height, c.width, c.height));
      cam.world_from_camera.translation = JsonVec3(cj, "center", cw);
      cam.world_from_camera.rotation =
          RotationFromJson(JsonField(cj, "orientation", cw), cw + ": orientation");
      if (cj.contains("photometry"))
        cam.photometry = PhotometryFromJson(cj["photometry"], cw + ": photometry");
    } else if (cj.contains("reason")) {
      cam.reason = JsonString(cj, "reason", cw);
    }
    c.cameras[i] = cam;
  }
  for (const char* key : {"array_fit", "bundle_adjustment"})
    if (j.contains(key)) c.summary[key] = j[key];
  return c;
}

CalibrationFile ReadCalibration(const std::filesystem::path& path) {
  const auto bytes = ReadFileBytes(path, kMaxJsonBytes, "calibration file");
  return CalibrationFromJson(
      ParseJsonBounded(std::string(bytes.begin(), bytes.end()), path.string()), path.string());
}

CalibrationFile ScaledCalibration(const CalibrationFile& cal, int width, int height) {
  if (width == cal.width && height == cal.height) return cal;
  const double sx = double(width) / cal.width, sy = double(height) / cal.height;
  if (width < 1 || height < 1 || std::abs(sx / sy - 1) > 2e-3)
    throw Error(
        fmt::format("a calibration of {}x{} images does not scale to {}x{}: another "
                    "aspect ratio (another field of view)",
                    cal.width, cal.height, width, height));
  CalibrationFile out = cal;
  out.width = width;
  out.height = height;
  for (CalibratedCamera& c : out.cameras) {
    CameraIntrinsics& k = c.intrinsics;
    k.width = width;
    k.height = height;
    k.fx *= sx;
    k.fy *= sy;
    // Pixel centres: x = i + 0.5 in the image's own units before and after.
    k.cx = (k.cx + 0.5) * sx - 0.5;
    k.cy = (k.cy + 0.5) * sy - 0.5;
  }
  return out;
}

}  // namespace lfcam
