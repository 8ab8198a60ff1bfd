#include "lfcam/share/quilt.h"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"

namespace lfcam {

const std::vector<QuiltPreset>& QuiltPresets() {
  // Looking Glass's recommended quilt for each display (its Bridge's defaults).
  static const std::vector<QuiltPreset> presets = {
      {"portrait", "Looking Glass Portrait", 3360, 3360, 8, 6, 0.75, 40},
      {"go", "Looking Glass Go", 4092, 4092, 11, 6, 0.5625, 54},
      {"16-landscape", "Looking Glass 16\" Spatial Display (landscape)", 5999, 5999, 7, 7,
       16.0 / 9.0, 50},
      {"16-portrait", "Looking Glass 16\" Spatial Display (portrait)", 5995, 6000, 11, 6, 0.5625,
       50},
      {"32-landscape", "Looking Glass 32\" Spatial Display (landscape)", 8190, 8190, 7, 7,
       16.0 / 9.0, 50},
      {"32-portrait", "Looking Glass 32\" Spatial Display (portrait)", 8184, 8184, 11, 6, 0.5625,
       54},
      {"65", "Looking Glass 65\"", 8192, 8192, 8, 9, 16.0 / 9.0, 40},
  };
  return presets;
}

const QuiltPreset& QuiltPresetNamed(const std::string& name) {
  std::string names;
  for (const QuiltPreset& preset : QuiltPresets()) {
    if (preset.name == name) return preset;
    names += (names.empty() ? "" : ", ") + preset.name;
  }
  throw UsageError(fmt::format("--preset {}: no such display; one of {}", name, names));
}

std::string QuiltLayout::suffix() const {
  // Looking Glass's own spelling: the aspect to at most five decimals, no trailing zeros.
  std::string a = fmt::format("{:.5f}", aspect);
  while (a.back() == '0') a.pop_back();
  if (a.back() == '.') a.pop_back();
  return fmt::format("_qs{}x{}a{}", cols, rows, a);
}

QuiltLayout LayoutQuilt(const QuiltPreset& preset, bool even) {
  QuiltLayout layout;
  layout.cols = preset.cols;
  layout.rows = preset.rows;
  layout.aspect = preset.aspect;
  layout.tile_width = preset.width / preset.cols;
  layout.tile_height = preset.height / preset.rows;
  if (even) {
    if (layout.width() % 2 != 0) --layout.tile_width;
    if (layout.height() % 2 != 0) --layout.tile_height;
  }
  layout.render_width = layout.tile_width;
  layout.render_height = std::max(1, int(std::lround(layout.tile_width / preset.aspect)));
  return layout;
}

double ArrayBaselineMm(const LightField& lf) {
  const ArrayPlane& array = lf.slab().uv;
  return (array.camera_center(0, array.cols - 1) - array.camera_center(0, 0)).norm();
}

std::vector<VirtualCameraParams> QuiltCameras(const VirtualCameraParams& centre,
                                              const QuiltLayout& layout, double baseline_mm) {
  if (!(baseline_mm >= 0) || !std::isfinite(baseline_mm))
    throw Error(fmt::format("baseline {} mm: must be zero or more", baseline_mm));
  const VirtualCameraParams sized =
      WithFrameSize(centre, layout.render_width, layout.render_height);
  const VirtualCamera camera(sized);  // checks the centre camera
  const double d = sized.focus_distance_mm;
  // tan(theta / 2) across the width: the pixel offset that moves the window back by x is
  // x W / (2 d tan(theta / 2)).
  const double tan_half = std::tan(0.5 * camera.field_of_view_rad());
  std::vector<VirtualCameraParams> cameras;
  const int n = layout.views();
  for (int k = 0; k < n; ++k) {
    const double x = n > 1 ? baseline_mm * (double(k) / (n - 1) - 0.5) : 0.0;
    VirtualCameraParams p = sized;
    p.eye = sized.eye + x * camera.u_c();
    p.look_at = sized.look_at + x * camera.u_c();
    p.principal_offset_px.x() += x * layout.render_width / (2.0 * d * tan_half);
    cameras.push_back(p);
  }
  return cameras;
}

cv::Rect QuiltTile(const QuiltLayout& layout, int view) {
  const int col = view % layout.cols, row = view / layout.cols;
  // Row 0 of tiles is the bottom one: the image's last tile_height rows.
  return {col * layout.tile_width, layout.height() - (row + 1) * layout.tile_height,
          layout.tile_width, layout.tile_height};
}

cv::Mat ToTile(const cv::Mat& view_srgb8, const QuiltLayout& layout) {
  if (view_srgb8.cols == layout.tile_width && view_srgb8.rows == layout.tile_height)
    return view_srgb8;
  cv::Mat tile;
  cv::resize(view_srgb8, tile, {layout.tile_width, layout.tile_height}, 0, 0, cv::INTER_AREA);
  return tile;
}

cv::Mat RenderQuilt(const LightField& lf, const QuiltLayout& layout,
                    const std::vector<VirtualCameraParams>& cameras, const FrameRenderer& renderer,
                    const FrameRenderOptions& options, const std::function<void()>& view_done) {
  if (int(cameras.size()) != layout.views())
    throw Error(fmt::format("a {}x{} quilt needs {} cameras, not {}", layout.cols, layout.rows,
                            layout.views(), cameras.size()));
  cv::Mat quilt(layout.height(), layout.width(), CV_8UC3, cv::Scalar::all(0));
  for (int k = 0; k < layout.views(); ++k) {
    const RenderResult result =
        renderer.Render(lf, VirtualCamera(cameras[std::size_t(k)]), options);
    ToTile(LinearToSrgb8Image(result.image), layout).copyTo(quilt(QuiltTile(layout, k)));
    if (view_done) view_done();
  }
  return quilt;
}

}  // namespace lfcam
