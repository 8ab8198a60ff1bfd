#pragma once
// Importing a light field someone else captured or rendered (docs/format.md, "Importing"): a
// folder of views on a regular grid of parallel cameras, named the Stanford light field
// archive's way (NAME_RR_CC_Y_X_.png) or the Blender camera-grid way (NAME_RR_CC_Y_X_F_W.jpg),
// or any folder of views with a description (lfcam-views.json). Each becomes what `lfcam build`
// reads, a capture manifest and a calibration of ideal cameras, so that imported views and a Pi
// array's photographs go through the one resampler (calib/lightfield_build.h).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/calib/calibration_file.h"
#include "lfcam/capture/session.h"

namespace lfcam {

inline constexpr const char* kViewsDescriptionName = "lfcam-views.json";

enum class GridNaming { kStanford, kBlender, kDescription };
std::string ToString(GridNaming naming);

struct GridView {
  int row = 0, col = 0;       // lfcam's grid: row 0 at the bottom, col 0 at the left
  std::string file;           // relative to the folder; empty when the view is missing
  double x_mm = 0, y_mm = 0;  // the centre on the camera plane: x right, y up (seen from behind)
};

struct ImportedGrid {
  GridNaming naming = GridNaming::kStanford;
  int rows = 0, cols = 0;
  int width = 0, height = 0;                        // every view's size
  double pitch_mm = 0;                              // the mean spacing between neighbours
  std::optional<double> focal_px;                   // from the description
  std::optional<double> focal_mm, sensor_width_mm;  // from Blender names or the description
  std::optional<double> st_distance_mm;             // from the description
  std::vector<GridView> views;                      // row-major, rows * cols
  std::vector<std::string> missing;  // "camera (r, c)" for each view not in the folder

  const GridView& view(int row, int col) const { return views[std::size_t(row * cols + col)]; }
};

// One file's name, parsed: NAME_RR_CC_Y_X_F_W (Blender) or NAME_RR_CC_Y_X[_] (Stanford), NAME
// anything; the archive's grid indices and the position numbers as named.
struct NamedView {
  std::string file;
  int rr = 0, cc = 0;
  double first = 0, second = 0;  // as named: -y and x (docs/format.md)
  std::optional<double> focal_mm, sensor_width_mm;
};
std::optional<std::pair<GridNaming, NamedView>> ParseViewName(const std::string& file);

// The grid an lfcam-views.json describes (files not checked); throws lfcam::Error naming `where`.
ImportedGrid GridFromDescription(const nlohmann::json& j, const std::string& where);

// Reads the folder: detects the naming (a description file wins), parses every name, checks
// that the views form a complete grid (unless `allow_missing`) of one image size. Throws
// lfcam::Error naming the file at fault.
ImportedGrid ScanGridFolder(const std::filesystem::path& dir, bool allow_missing);

struct ImportOptions {
  std::optional<double> st_distance_mm;  // default: the description's, else estimated
  std::optional<double> focal_px;        // default: the description's or the names'
  std::optional<double> focal_mm, sensor_width_mm;
};

struct ImportedSession {
  CaptureManifest manifest;     // one scene shot, files relative to the folder
  CalibrationFile calibration;  // ideal cameras at the named positions, looking along -z
  double st_distance_mm = 0;
  bool st_distance_estimated = false;
  double focal_px = 0;
};

// The manifest and calibration `build` needs. The world frame: x right, y up, z toward the
// cameras, which sit on the plane z = st distance and look along -z; the st-plane is z = 0 and
// its window is what the central camera of the grid sees there. Throws lfcam::Error when the
// intrinsics are not known (give --focal-px or --focal-mm and --sensor-width-mm).
ImportedSession MakeImportedSession(const std::filesystem::path& dir, const ImportedGrid& grid,
                                    const ImportOptions& options);

// The depth most of the scene lies at: from the disparity between the two outermost views of
// the middle row (or column), by phase correlation; the default st distance. Throws
// lfcam::Error when the views show no measurable disparity.
double EstimateDominantDepthMm(const std::filesystem::path& dir, const ImportedGrid& grid,
                               double focal_px);

}  // namespace lfcam
