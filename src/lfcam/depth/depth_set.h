#pragma once
// The depth maps of a light field's views, all in one depth range: what depth-aware rendering
// reads (`lfcam render --interpolation depth --depth DIR`), written by `lfcam depth --all`;
// EstimateDepthSet (depth/plane_sweep.h) fills one in.
//
// On disk, a folder: depth.json (format "lfcam-depth-set", version 1: the light field's grid
// and st resolution, the range, one entry per view with its file) and per view
// depth_RR_CC.png with depth_RR_CC.confidence.png (depth/depth_map.h's files), plus
// preview.png, the central view's colour preview.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/depth/depth_map.h"

namespace lfcam {

class DepthSet {
 public:
  DepthSet() = default;
  explicit DepthSet(const LightFieldDims& dims) : dims_(dims), maps_(dims.view_count()) {}

  const LightFieldDims& dims() const { return dims_; }
  bool has(int row, int col) const { return maps_[index(row, col)].has_value(); }
  const DepthMap& at(int row, int col) const;  // throws lfcam::Error when missing
  void set(DepthMap map);                      // checks its shape against dims()
  int count() const;                           // views with a map
  // The union of the maps' ranges.
  DepthRange range() const;

 private:
  std::size_t index(int row, int col) const { return std::size_t(row) * dims_.cols + col; }
  LightFieldDims dims_;
  std::vector<std::optional<DepthMap>> maps_;
};

// Writes the set's folder; `length_unit` (WorldLengthUnit of its light field) goes into
// depth.json, each map's text chunk and the preview's scale.
void WriteDepthSet(const std::filesystem::path& dir, const DepthSet& set,
                   const std::string& source_name, const std::string& length_unit = "mm");
// One view's entry in depth.json.
struct DepthSetEntry {
  int row = 0, col = 0;
  std::string file;  // a plain name in the set's folder
};
// depth.json's text, checked against the light field's dims: its views' entries (at least one;
// rows and columns on the grid, names that stay in the folder). Throws lfcam::Error naming
// `where`.
std::vector<DepthSetEntry> ParseDepthSetIndex(std::string_view text, const LightFieldDims& dims,
                                              const std::string& where);
// What of a depth set's folder to read.
struct DepthSetRead {
  // The confidence maps (depth_RR_CC.confidence.png) too: export's points leave out
  // unconfident samples; the renderers read the depths alone.
  bool confidence = true;
  // The views whose maps to read, row-major (a frame's DepthViewsNeeded); empty: every view the
  // index lists.
  std::vector<bool> views;
};
// Reads a depth set for `lf`, its views' files decoded in parallel; throws lfcam::Error naming
// the file when one does not match (the first in depth.json's order, whatever the threads did).
DepthSet ReadDepthSet(const std::filesystem::path& dir, const LightField& lf,
                      const DepthSetRead& what = {});
// What a renderer reads: the depths of `views` (empty: all).
DepthSetRead DepthsForRendering(std::vector<bool> views = {});

std::string DepthFileName(int row, int col);  // depth_RR_CC.png

}  // namespace lfcam
