#pragma once
// `lfcam export FILE --format web --out DIR`: a light field anyone can open in a browser. DIR
// holds index.html (the page), lfcam-web.js (its WebGL2 renderer: share/web/) and
// lightfield.js (the light field: its geometry and every view as a JPEG in a data URL, so that
// the page works from disk, where browsers fetch nothing, as well as from any static server).
// No build step, nothing fetched from the network.
//
// It fits phones: each view is one layer of a texture array, no side over 4096 px, the whole
// array within a texture budget; the views' resolution and JPEG quality are chosen so that the
// folder stays within a download budget, the full resolution and quality 90 first, then lower
// quality, then half the resolution, and so on. What was given up is said (report.note), on the
// page too.
#include <cstdint>
#include <filesystem>
#include <string>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

struct WebExportOptions {
  std::string name = "light field";  // the page's title
  // The page's first view: focal length, focus distance, aperture, breathing (the eye starts
  // at the array's centre; the canvas takes the window's size unless the URL gives one).
  VirtualCameraParams camera;
  std::uint64_t max_download_bytes = 30'000'000;
  std::uint64_t max_texture_bytes = 256ull << 20;  // the views on the GPU, 4 bytes a texel
  int max_texture_side = 4096;
  int jpeg_quality = 90;  // the first quality tried
};

struct WebExportReport {
  std::uint64_t download_bytes = 0;  // the folder's files together
  int view_width = 0, view_height = 0;
  int scale = 1;  // the light field's samples per view sample, each way
  int jpeg_quality = 0;
  std::string note;  // what the page gives up, for people
};

// Throws lfcam::Error when even the smallest choice does not fit the budget (naming it), or
// `out_dir` exists and is not empty.
WebExportReport ExportWeb(const LightField& lf, const WebExportOptions& options,
                          const std::filesystem::path& out_dir);

}  // namespace lfcam
