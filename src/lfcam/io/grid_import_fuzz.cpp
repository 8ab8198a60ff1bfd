// libFuzzer target: what `lfcam import` reads before any image: the views' file names (every
// naming: Stanford, Blender camera grid, HCI, unit grid, sequence) and lfcam-views.json (versions 1
// and 2: a rectified rig's zero-disparity plane or principal points, then its geometry resolved),
// and the name a missing view of a positioned grid would have.
#include <cstdint>
#include <string>
#include <string_view>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/io/rectified_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (const auto naming :
       {lfcam::GridNaming::kStanford, lfcam::GridNaming::kBlender, lfcam::GridNaming::kHci,
        lfcam::GridNaming::kUnitGrid, lfcam::GridNaming::kSequence})
    (void)lfcam::ParseViewName(std::string(text.substr(0, 256)), naming);
  // A missing view's name from two beside it (the input's halves, split at a newline).
  if (const auto cut = text.find('\n'); cut != std::string_view::npos && cut < 256)
    for (const auto naming : {lfcam::GridNaming::kStanford, lfcam::GridNaming::kBlender})
      (void)lfcam::NameWithPositionsUnknown(std::string(text.substr(0, cut)),
                                            std::string(text.substr(cut + 1, 256)), naming);
  try {
    lfcam::ImportedGrid grid =
        lfcam::GridFromDescription(lfcam::ParseJsonBounded(text, "fuzz"), "fuzz");
    if (grid.rig == lfcam::RigModel::kRectified && grid.rows * grid.cols <= 4096) {
      grid.width = 64, grid.height = 48;
      for (auto& v : grid.views) v.file = v.file.empty() ? "x.png" : v.file;
      const auto geometry = lfcam::ResolveRectifiedGeometry(grid, {});
      (void)geometry.PrincipalPoint(1, 2);
    }
  } catch (const lfcam::Error&) {
  }
  return 0;
}
