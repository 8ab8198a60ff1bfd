#pragma once
// `import`'s flags and its work: a light field from a folder of views someone else made (the
// Stanford archive's, a Blender camera grid's, the HCI benchmark's, plenoptic views, or any
// described in lfcam-views.json): a rectified rig's views stored sample for sample, a parallel
// rig's through the same resampler as `build` (docs/format.md, "Importing"). Shared by
// `lfcam import` and the Python module's lfcam.import_views.
#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lfcam/cli/keyword_arguments.h"
#include "lfcam/core/lightfield.h"
#include "lfcam/io/grid_import.h"

namespace lfcam::cli {

struct ImportedLightField {
  LightField lightfield;
  // What was imported and how (rig, naming, pitch, focal length, the st-plane, what was
  // assumed or filled): `lfcam import --json`'s summary, without "out".
  nlohmann::json summary;
  std::vector<std::string> ignored;  // files in the folder that are not views
};

struct ImportFlags {
  std::string dir;
  std::string st_res, st_domain, resampling = "linear", chroma = "guided", naming = "auto",
                                 rig = "auto", st_windows = "views", grid_shape;
  double st_distance = 0, focal_px = 0, focal_mm = 0, sensor_width_mm = 0, pitch_mm = 0;
  int lenslet = 0;  // a lenslet image's views a side (0: found from its pixels)
  bool allow_missing = false;
  bool keep_dark_views = false;
  bool flip_rows = false;  // the rows taken in reverse (row index or y counting the other way)
  bool flip_cols = false;  // the columns taken in reverse
  bool swap_axes = false;  // the names' rows taken as columns and columns as rows (first)
  bool keep_axes = false;  // the names' axes kept when the views' parallax disagrees with them

  // Every flag but the folder, --out, --compress and the printing ones (the command's).
  void AddTo(CLI::App& command);
  // Checks the flags (UsageError naming the flag) and imports `dir`, with a progress bar unless
  // `quiet`: a folder of views, or one lenslet image (io/lenslet_image.h). Throws lfcam::Error
  // naming the file for a folder or an image it cannot read.
  ImportedLightField Run(bool quiet) const;

 private:
  // `dir` a lenslet image: split into its views (in a temporary folder, removed after), which are
  // imported as a plenoptic camera's views are; the summary and the file say where they came from.
  ImportedLightField RunLenslet(bool quiet) const;
  // Checks the names' axes against the views' parallax (io/parallax_axes.h): exchanges the rows
  // and columns of `grid`, then reverses its rows or columns, where --swap-axes, --flip-rows or
  // --flip-cols say so; without them or --keep-axes, does what the views say (exchanged axes
  // swapped back, then a reversed axis reversed), and throws lfcam::Error where the views agree
  // with no reading. What it found and did, for the summary.
  nlohmann::json CheckAxes(ImportedGrid& grid) const;
  // A rectified rig's near and far told by its occlusions (depth/occlusion_order.h): where they
  // say the rig stands turned half a turn, and no axis flag was given, `grid` is taken turned
  // (its rows and columns in reverse) and imported again into `imported`. What it found and
  // did, for the summary.
  nlohmann::json CheckOcclusionOrder(ImportedLightField& imported, ImportedGrid& grid,
                                     const ImportOptions& options, bool quiet) const;

  CLI::Option *st_res_ = nullptr, *st_domain_ = nullptr, *resampling_ = nullptr,
              *st_windows_ = nullptr;
};

// lfcam.import_views(dir, **keywords): the keywords through `lfcam import`'s own flags
// (cli/keyword_arguments.h). Throws UsageError with the keyword's name.
struct ImportRequest {
  std::unique_ptr<CLI::App> parser;  // the flags keep pointers into it: kept with them
  ImportFlags flags;
};
std::unique_ptr<ImportRequest> ParseImportKeywords(const std::string& dir,
                                                   const std::vector<KeywordArgument>& arguments);

}  // namespace lfcam::cli
