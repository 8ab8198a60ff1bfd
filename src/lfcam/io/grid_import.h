#pragma once
// Importing a light field someone else captured or rendered (docs/format.md, "Importing"): a
// folder of views on a regular grid of cameras, named the Stanford light field archive's way
// (NAME_RR_CC_Y_X_.png), the Blender camera-grid way (NAME_RR_CC_Y_X_F_W.jpg), the HCI
// benchmark's way (input_CamNNN.png, with parameters.cfg), as a plain grid of indices
// (NAME_RR_CC.png or RR_CC.png: plenoptic sub-aperture views), as one numbered sequence
// (NAMENNN.png, taken row by row from the top left as the HCI benchmark numbers its cameras),
// or any folder of views with a description (lfcam-views.json).
//
// Two rigs (DESIGN.md, "Rigs of the research community"): parallel cameras with centred sensors
// (Blender grids) become what `lfcam build` reads, a capture manifest and a calibration of ideal
// cameras (io/parallel_import.h), so that their views and a Pi array's photographs go through
// the one resampler (calib/lightfield_build.h); rectified rigs, whose shifted sensors give one
// plane zero disparity (Stanford, HCI, plenoptic), are stored sample for sample
// (io/rectified_import.h).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/calib/calibration_file.h"
#include "lfcam/io/hci_parameters.h"
#include "lfcam/io/view_names.h"
#include "lfcam/session/session.h"

namespace lfcam {

inline constexpr const char* kViewsDescriptionName = "lfcam-views.json";

inline constexpr const char* kHciParametersName = "parameters.cfg";

// Parallel cameras with centred sensors (zero disparity at infinity), or a rectified rig: parallel
// cameras whose sensors are shifted so that the plane at one distance has zero disparity.
enum class RigModel { kParallel, kRectified };
std::string ToString(RigModel rig);
RigModel RigModelFromString(const std::string& name);  // throws lfcam::Error
// The rig a naming implies: Blender grids are parallel; the Stanford archive's, the HCI
// benchmark's and plenoptic views are rectified.
RigModel DefaultRig(GridNaming naming);

struct GridView {
  int row = 0, col = 0;       // lfcam's grid: row 0 at the bottom, col 0 at the left
  std::string file;           // relative to the folder; empty when the view is missing
  double x_mm = 0, y_mm = 0;  // the centre on the camera plane: x right, y up (seen from behind)
  std::optional<Vec2> principal_point;  // OpenCV's (cx, cy), px: from the description
};

struct ImportedGrid {
  GridNaming naming = GridNaming::kStanford;
  int rows = 0, cols = 0;
  int width = 0, height = 0;                        // every view's size
  double pitch_mm = 0;                              // the mean spacing between neighbours
  std::optional<double> focal_px;                   // from the description
  std::optional<double> focal_mm, sensor_width_mm;  // from Blender names or the description
  std::optional<double> st_distance_mm;             // from the description
  RigModel rig = RigModel::kParallel;               // as the naming or description implies
  // The zero-disparity plane's distance (a rectified rig): the description's or parameters.cfg's.
  std::optional<double> zero_disparity_mm;
  bool positions_known = true;  // false: the names give indices only (unit pitch)
  // A unit grid whose names run row and column together (NAMERRCC): the digits of each.
  int joined_digits = 0;
  std::optional<HciParameters> hci;  // parameters.cfg, when the folder has one
  std::vector<GridView> views;       // row-major, rows * cols
  std::vector<std::string> missing;  // "camera (r, c)" for each view not in the folder
  std::vector<std::string> ignored;  // images in the folder that are not views (HCI)
  // How the views' files encode them (from their headers): whatever they are, a light field keeps
  // 8 bits a channel of sRGB colour.
  bool sixteen_bit = false;  // some view has 16 bits a channel
  bool alpha = false;        // some view has an alpha channel (left out, not composited)
  bool grey = false;         // every view is grey (stored as three equal channels)

  const GridView& view(int row, int col) const { return views[std::size_t(row * cols + col)]; }
};

// The grid an lfcam-views.json describes (files not checked); throws lfcam::Error naming `where`.
ImportedGrid GridFromDescription(const nlohmann::json& j, const std::string& where);

// The shape of a grid whose names do not give it (`lfcam import --grid`).
struct GridShape {
  int rows = 0, cols = 0;
};

// Reads the folder: detects the naming (a description file wins; else the one naming under
// which every view's name parses into distinct grid positions: a folder that parses several
// ways, or none, is refused with the reason), parses every name, checks that the views form a
// complete grid (unless `allow_missing`) of one image size. `naming` forces one. `shape`, where
// given, is the grid's: for a numbered sequence, or HCI views without a parameters.cfg, whose
// names do not say it; names that give another shape are refused. Throws lfcam::Error naming
// the file at fault.
ImportedGrid ScanGridFolder(const std::filesystem::path& dir, bool allow_missing,
                            std::optional<GridNaming> naming = std::nullopt,
                            std::optional<GridShape> shape = std::nullopt);

// An archive unpacked as it comes often puts its views one or two folders down (the Stanford
// archive's rectified/, a zip's own folder). Where `dir` holds neither views (two or more .png or
// .jpg) nor a description itself, the one folder within two levels of it that does, skipping
// hidden folders and __MACOSX; nullopt where `dir` holds views itself, or nothing under it does
// (ScanGridFolder then says what is missing). Throws lfcam::Error naming them where several do:
// nothing is guessed.
std::optional<std::filesystem::path> ViewsSubfolder(const std::filesystem::path& dir);

// What the scan took for granted, for the import's `note:` lines and the file's import.notes,
// whatever the rig: a numbered sequence's reading order, and views of 16 bits a channel, with
// alpha, or grey, stored as 8-bit sRGB colour.
std::vector<std::string> NamingNotes(const ImportedGrid& grid);

struct ImportOptions {
  // Parallel: the st-plane's distance (default: the description's, else estimated); rectified:
  // the zero-disparity plane's (default: the description's or parameters.cfg's, else assumed).
  std::optional<double> st_distance_mm;
  std::optional<double> focal_px;  // default: the description's, parameters.cfg's or the names'
  std::optional<double> focal_mm, sensor_width_mm;
  std::optional<double> pitch_mm;  // the cameras' spacing when the names give indices only
  std::optional<RigModel> rig;     // default: as the naming or description implies
  // Rectified, where no distance is known: how far behind the zero-disparity plane infinity is
  // assumed to lie, px of disparity between neighbours (default kAssumedInfinityDisparityPx;
  // `lfcam import` sets it from the parallax the views show).
  std::optional<double> infinity_disparity_px;
  // Rectified: the scene's largest parallax between neighbouring views, px, as the views show it
  // (`lfcam import` measures it: MeasureParallaxAxes); what the depth sweep brackets
  // (RectifiedGeometry::scene_disparity_px).
  std::optional<double> scene_parallax_px;
  // Rectified: views that recorded black, or nearly, filled from their neighbours (false: kept
  // as they are, `--keep-dark-views`).
  bool fill_dark_views = true;
};

}  // namespace lfcam
