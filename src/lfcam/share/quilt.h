#pragma once
// Looking Glass quilts (`lfcam export --format quilt`): the grid of views a Looking Glass
// holographic display shows. The display's views are off-axis cameras on a horizontal line, all
// looking the same way, their sensors shifted so that they share one window on the plane of
// focus (the display's zero-parallax plane: what lies there appears on the glass, nearer things
// in front of it, farther ones behind). View 0 is the leftmost camera; the quilt holds it in its
// bottom-left tile, then left to right and bottom to top. The file's name ends in
// `_qs{cols}x{rows}a{aspect}` (a the display's width over height), which is how the display's
// software knows the layout.
//
// A light field's views span only its array: the quilt's cameras spread over the array's width
// (its outer camera centres, or --baseline) and the display's view cone shows that spread, so
// depth on the display is the array's parallax scaled to the cone, as every light field shown on
// such a display is.
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/frame_renderer.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

// A display family's quilt (Looking Glass's own defaults for each display).
struct QuiltPreset {
  std::string name;
  std::string display;
  int width = 0, height = 0;  // the whole quilt, pixels
  int cols = 0, rows = 0;
  double aspect = 1;          // the display's width over height
  double view_cone_deg = 40;  // the angle its views span
};
const std::vector<QuiltPreset>& QuiltPresets();
// Throws lfcam::UsageError listing the names when there is none of that name.
const QuiltPreset& QuiltPresetNamed(const std::string& name);

struct QuiltLayout {
  int cols = 0, rows = 0;
  int tile_width = 0, tile_height = 0;      // a tile in the quilt
  int render_width = 0, render_height = 0;  // a view as rendered (square pixels, the aspect)
  double aspect = 1;
  int views() const { return cols * rows; }
  int width() const { return cols * tile_width; }
  int height() const { return rows * tile_height; }
  // "_qs8x6a0.75"
  std::string suffix() const;
};
// Tiles of the quilt's size over its grid; each view rendered at the tile's width and the
// display's aspect (a tile whose shape differs from the display's is that render scaled, as the
// display stretches it back). `even`: the quilt's width and height made even (H.264's 4:2:0) by
// narrowing the tiles a pixel where needed.
QuiltLayout LayoutQuilt(const QuiltPreset& preset, bool even = false);

// The views' cameras: `centre` (its eye the middle of the line, its focus distance the plane of
// zero parallax, its lens) moved along its own right vector u_c from -baseline/2 to
// +baseline/2, each with the principal offset that keeps the window on the plane of focus, at
// the layout's render size. Throws lfcam::Error.
std::vector<VirtualCameraParams> QuiltCameras(const VirtualCameraParams& centre,
                                              const QuiltLayout& layout, double baseline_mm);
// The default baseline: the distance between the array's outer camera centres along a row.
double ArrayBaselineMm(const LightField& lf);

// Renders every view and lays them out; sRGB, CV_8UC3 (RGB). `view_done` (may be empty) is
// called after each view.
cv::Mat RenderQuilt(const LightField& lf, const QuiltLayout& layout,
                    const std::vector<VirtualCameraParams>& cameras, const FrameRenderer& renderer,
                    const FrameRenderOptions& options, const std::function<void()>& view_done = {});

// The tile of view k as the quilt holds it (bottom-left first, left to right, bottom to top).
cv::Rect QuiltTile(const QuiltLayout& layout, int view);
// A view's render (sRGB, render size) as its tile holds it.
cv::Mat ToTile(const cv::Mat& view_srgb8, const QuiltLayout& layout);

}  // namespace lfcam
