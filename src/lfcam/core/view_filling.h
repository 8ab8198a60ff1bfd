#pragma once
// Filling a view the grid lacks (`build` and `import --allow-missing`): from its nearest
// neighbours on the camera grid, averaged in linear light.
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
