#pragma once
// How the research community names a grid's views (docs/format.md, "Importing"): the Stanford
// light field archive's NAME_RR_CC_Y_X_.png, the Blender camera grid's NAME_RR_CC_Y_X_F_W.jpg,
// the HCI benchmark's input_CamNNN.png, a plain grid of indices (NAME_RR_CC.png: plenoptic
// sub-aperture views), one numbered sequence (NAMENNN.png), or a description (lfcam-views.json);
// one file's name parsed each way (io/grid_import.h reads a whole folder).
#include <optional>
#include <string>

namespace lfcam {

enum class GridNaming { kStanford, kBlender, kDescription, kHci, kUnitGrid, kSequence };
std::string ToString(GridNaming naming);
GridNaming GridNamingFromString(const std::string& name);  // throws lfcam::Error

// One file's name, parsed the way `naming` names views: NAME_RR_CC_Y_X_F_W (Blender),
// NAME_RR_CC_Y_X[_] (Stanford), input_CamNNN (HCI: rr = NNN), [NAME_]RR_CC (unit grid; with '-'
// in place of '_' where the name has no '_'), NAMENNN (sequence: rr = NNN, up to 6 digits), NAME
// anything; the grid indices and the position numbers as named. Nullopt when it does not parse
// that way (kDescription never parses).
struct NamedView {
  std::string file;
  int rr = 0, cc = 0;
  double first = 0, second = 0;  // as named: -y and x (docs/format.md)
  std::optional<double> focal_mm, sensor_width_mm;
};
std::optional<NamedView> ParseViewName(const std::string& file, GridNaming naming);

// The name of a view missing from a grid whose names carry positions (Stanford's, Blender's):
// `row_file`'s name (a view in its row) with `col_file`'s column index (a view in its column)
// and each position a '*', which only the missing file could say (out_03_05_*_*_.png). Nullopt
// for other namings, or names that do not parse.
std::optional<std::string> NameWithPositionsUnknown(const std::string& row_file,
                                                    const std::string& col_file, GridNaming naming);

}  // namespace lfcam
