#pragma once
// Filling a view the grid lacks (`build` and `import --allow-missing`) or one too dark to be a
// photograph of the scene: from its nearest neighbours on the camera grid, averaged in linear
// light.
#include <string>
#include <utility>
#include <vector>

#include "lfcam/core/lightfield.h"

namespace lfcam {

// The views at the smallest grid distance from (row, col) among those `present` (row-major,
// rows * cols entries); empty when none is.
std::vector<std::pair<int, int>> NearestPresentViews(int rows, int cols,
                                                     const std::vector<bool>& present, int row,
                                                     int col);

// A view whose brightness (its three channels' means over the middle of the frame) is under
// this share of the median view's recorded black, or nearly: a plenoptic camera's views beyond
// its main lens's aperture (the corners of a 15 x 15 decode), a camera whose exposure failed or
// whose lens was covered. Such a view is no photograph of the scene, and averaged into a render
// it would darken it (docs/format.md).
inline constexpr double kDarkViewShare = 1.0 / 16;

// The views of an srgb8 light field among those `read` (row-major, one a view) whose brightness
// (the sum of the three channels' means over the middle three quarters of the view each way) is
// under kDarkViewShare of the median read view's. None where that median is itself black.
std::vector<std::pair<int, int>> DarkViews(const LightField& lf, const std::vector<bool>& read);

// What `import` and `build` say of the views DarkViews found (`labels`: each view's name), in a
// `note:`.
std::string DarkViewsNote(const std::vector<std::string>& labels);

// View (row, col) of an srgb8 light field becomes the mean, in linear light, of the views `from`.
void FillViewWithMean(LightField& lf, int row, int col,
                      const std::vector<std::pair<int, int>>& from);

// "camera (r, c) from (r, c), (r, c)": what a report says of a filled view.
std::string FilledViewLabel(int row, int col, const std::vector<std::pair<int, int>>& from);

// The views `lf` records as filled rather than photographed (grid row, col): its metadata's
// `filled_views` (build) or `import.filled_views` (import), whose entries are objects with `row`
// and `col`, or, in files imported before 2026-12-04, FilledViewLabel's strings. Entries of
// another shape, or outside the grid, are passed over.
std::vector<std::pair<int, int>> FilledViews(const LightField& lf);
// The same from a light field's metadata and grid (a file's header, `lfcam info`).
std::vector<std::pair<int, int>> FilledViews(const nlohmann::json& metadata, int rows, int cols);
// Row-major, one a view: false where FilledViews names the view.
std::vector<bool> PhotographedViews(const LightField& lf);

}  // namespace lfcam
