#pragma once
// Importing a rectified rig (DESIGN.md, "Rigs of the research community"): parallel cameras on
// a grid whose sensors are shifted so that the plane at distance Z0 has zero disparity. A camera
// at grid offset b from the reference has its principal point moved by f b / Z0 px, so every
// camera maps the plane at Z0 onto the same pixels: put the st-plane there, on the window the
// views cover, and each photograph's pixels are st samples as they stand. The views are stored
// sample for sample (no resampling), each with the camera that took it (its position and
// shifted principal point), so `render --as-camera` reproduces them.
//
// World frame: x right, y up (seen from behind the cameras), z toward the cameras; the cameras
// on the plane z = Z0 looking along -z, the st-plane z = 0. Pixel (x, y) of every view (OpenCV's:
// centres at integers, y down) is st sample (k, l) = (x, H - 1 - y).
//
// When a data set publishes no focal length or units (the Stanford archive, plenoptic views),
// any consistent choice renders the same images: lfcam takes a focal length of max(W, H) px, a
// pitch of 1 mm where the names give indices only, and puts the zero-disparity plane where
// infinity lies ImportOptions::infinity_disparity_px behind it in disparity (`lfcam import`: twice
// the parallax the views show; kAssumedInfinityDisparityPx where unmeasured); what was assumed is
// reported and recorded in the file's metadata.
#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/io/grid_import.h"

namespace lfcam {

inline constexpr double kAssumedInfinityDisparityPx = 8.0;

// How far either side of zero disparity a scene whose views show `parallax_px` between
// neighbours (their largest) is taken to reach: twice that, rounded up to a whole px, at least 1
// (where `lfcam import` puts infinity when no distance is known, and what depth sweeps).
double SceneBracketPx(double parallax_px);

struct RectifiedGeometry {
  double focal_px = 0;
  double zero_disparity_mm = 0;  // Z0: the st-plane's distance from the cameras
  double pitch_mm = 0;
  Vec2 reference_principal_point = Vec2::Zero();  // OpenCV's (cx, cy) at the grid's centre
  Vec2 reference_xy_mm = Vec2::Zero();            // the grid's centre on the camera plane
  std::vector<std::string> assumed;  // what the data set did not say, as chosen (for the user)
  std::vector<std::string> notes;    // what the data set said that was adapted to the views
  bool metric = true;                // false: no scale known, the cameras' spacing taken as 1 unit
  // The disparities (px between neighbours) within which the views show the scene, {farthest,
  // nearest} (<= 0 <= ): twice the parallax they show (ImportOptions::scene_parallax_px, a whole
  // px, at least 1), joined to parameters.cfg's disp_min .. disp_max widened by half its span.
  // Recorded in the file (import.scene_disparity_px), where the depth range's coarse sweep
  // brackets it, whatever the units or wherever infinity lies. Nullopt where neither is known.
  std::optional<std::array<double, 2>> scene_disparity_px;

  // Camera at (x, y) mm on the camera plane: its principal point (OpenCV's convention).
  Vec2 PrincipalPoint(double x_mm, double y_mm) const;
  // Disparity (px between neighbours, positive nearer than Z0) of depth Z, and back.
  double DisparityOfDepth(double depth_mm) const;
};

// The geometry from the flags, the description, parameters.cfg or the names, in that order,
// else assumed (see above). Throws lfcam::Error when they contradict one another (a description
// whose principal points do not fit one zero-disparity plane: the view named).
RectifiedGeometry ResolveRectifiedGeometry(const ImportedGrid& grid, const ImportOptions& options);

struct RectifiedImportReport {
  std::vector<std::string> filled;  // "camera (r, c) from (r, c), ..." for each filled view
  // "FILE (r, c)" for each view too dark to be a photograph of the scene (filled, above)
  std::vector<std::string> dark;
  double seconds = 0;
};

// Reads every view into a light field of the views' own size, sample for sample. Missing views
// (`grid.missing`, allowed by the scan) and, with `fill_dark_views`, views darker than
// kDarkViewShare of the median view's brightness (DarkViews) are filled with the mean, in linear
// light, of their nearest present neighbours. Throws lfcam::Error naming the file that cannot be
// read.
LightField ImportRectifiedViews(const std::filesystem::path& dir, const ImportedGrid& grid,
                                const RectifiedGeometry& geometry,
                                const std::function<void()>& view_done = {},
                                RectifiedImportReport* report = nullptr,
                                bool fill_dark_views = true);

}  // namespace lfcam
