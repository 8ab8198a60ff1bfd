#pragma once
// A grid of parallel cameras with centred sensors (a Blender grid, a described folder) imported
// as what `lfcam build` reads: a capture manifest and a calibration of ideal cameras at the
// views' positions, the st-plane at the scene's dominant depth, moved to where neighbouring views
// lie a whole number of samples apart (DESIGN.md, "Rigs of the research community";
// io/rectified_import.h takes the rectified rigs).
#include <filesystem>
#include <optional>
#include <utility>

#include "lfcam/calib/calibration_file.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/session/session.h"

namespace lfcam {

struct ImportedSession {
  CaptureManifest manifest;     // one scene shot, files relative to the folder
  CalibrationFile calibration;  // ideal cameras at the named positions, looking along -z
  double st_distance_mm = 0;
  bool st_distance_estimated = false;
  // Estimated, then moved to where neighbouring views lie a whole number of samples apart on
  // the st-plane (WholeSampleStDistance): the estimate, and that number.
  std::optional<double> st_distance_unsnapped_mm;
  int samples_between_neighbours = 0;
  double focal_px = 0;
};

// The st-plane distance nearest `distance_mm` at which neighbouring cameras of a regular grid of
// parallel cameras see the plane a whole number n >= 1 of samples (pixels) apart: every view's
// pixels then fall on st samples (the window centred on the grid moved by half a sample where a
// count is even and n odd), and the build's resampling copies them. Returns the distance
// and n; nullopt when the cameras are not on a regular grid (to within 0.001 px).
// Half a sample where `count` cameras (even) lie n (odd) samples apart, else 0.
double HalfSample(int count, int samples_between_neighbours);
std::optional<std::pair<double, int>> WholeSampleStDistance(const ImportedGrid& grid,
                                                            double focal_px, double distance_mm);

// The manifest and calibration `build` needs. The world frame: x right, y up, z toward the
// cameras, which sit on the plane z = st distance and look along -z; the st-plane is z = 0 and
// its window is what the central camera of the grid sees there; the calibration's st domain
// covers what every camera sees there (the window widened by the grid's extent). Throws
// lfcam::Error when the intrinsics are not known (give --focal-px or --focal-mm and
// --sensor-width-mm).
ImportedSession MakeImportedSession(const std::filesystem::path& dir, const ImportedGrid& grid,
                                    const ImportOptions& options);

// The depth most of the scene lies at: from the disparity between the two outermost views of
// the middle row (or column), by phase correlation; the default st distance. Throws
// lfcam::Error when the views show no measurable disparity.
double EstimateDominantDepthMm(const std::filesystem::path& dir, const ImportedGrid& grid,
                               double focal_px);

}  // namespace lfcam
