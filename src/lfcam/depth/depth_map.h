#pragma once
// A depth map for one view of a light field, and its files.
//
// Depth here is the distance of a scene point from the camera array's plane, measured along the
// viewing direction -n_ca, in millimetres: D(P) = n_ca . (p_ca - P). It is the same number for
// every camera that sees P (the plane-sweep's planes are D = const), which is what makes depth
// maps of different views comparable (occlusion tests) and what `--depth-range` means.
//
// In memory a map follows the light field's sample layout: row l of the matrix is st row l
// (bottom-up), column k is st sample k, so map(l, k) is the depth of what view (row, col) sees
// through st sample (k, l).
//
// On disk (docs/format.md, "Depth maps"): a 16-bit grey PNG, upright like the exported views
// (top row = highest t). 0 = unknown; 1 .. 65535 encode near .. far linearly. The range and the
// view are in the PNG's text chunks (key "lfcam-depth", a JSON object; also the plain keys
// "depth_near_mm" and "depth_far_mm" for other tools). Beside it: an 8-bit confidence PNG
// (0 .. 255 for 0 .. 1) and a colour preview for people.
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace lfcam {

struct DepthRange {
  double near_mm = 0, far_mm = 0;  // 0 < near < far
  // Where EstimateDepthRange found the scene, before the margin it adds (0: near_mm and far_mm,
  // as for a range given): what says how far apart the views see the scene (not stored).
  double found_near_mm = 0, found_far_mm = 0;
  bool valid() const { return near_mm > 0 && far_mm > near_mm; }
  double scene_near_mm() const { return found_near_mm > 0 ? found_near_mm : near_mm; }
  double scene_far_mm() const { return found_far_mm > 0 ? found_far_mm : far_mm; }
};

struct DepthMap {
  int row = 0, col = 0;  // the view
  cv::Mat depth;         // CV_32FC1, n_t x n_s, mm (D above); NaN where unknown
  cv::Mat confidence;    // CV_32FC1, same shape, 0 .. 1; empty when not known
  DepthRange range;      // the range the map was estimated (or is stored) in
  // How the estimate read the views (not stored in the file): the reference view's noise in
  // 8-bit levels, its texture's share near the sampling limit (depth/view_sharpness.h), and the
  // width in samples of the Gaussian its neighbours were read through (0: Keys' cubic;
  // docs/depth.md, "Noisy views", "Sharp views").
  double noise_levels = 0, near_nyquist_share = 0, read_sigma = 0;
  // The Gaussian (samples) every view was blurred by first where the views are finer than the
  // cameras they were built from (0: none; docs/depth.md, "Views finer than their cameras").
  double camera_blur_sigma = 0;
  int reach = 0;  // the views compared: those up to this many grid steps away (not stored)
  // The views within reach left out as too dark to match the reference (grid row, col; not
  // stored; CostVolumeOptions::equalise_brightness).
  std::vector<std::pair<int, int>> views_too_dark;

  int n_s() const { return depth.cols; }
  int n_t() const { return depth.rows; }
};

// The file names that go with a depth PNG: PATH.confidence.png and PATH.preview.png beside
// "PATH.png" (the extension replaced).
std::filesystem::path ConfidencePathFor(const std::filesystem::path& depth_png);
std::filesystem::path PreviewPathFor(const std::filesystem::path& depth_png);

// The 16-bit PNG's bytes (range and view in text chunks; `extra` JSON fields are added to the
// "lfcam-depth" chunk).
std::string EncodeDepthPng(const DepthMap& map, const std::string& extra_json = "{}");
// Reads a depth PNG written by EncodeDepthPng (the confidence is not read: ReadConfidencePng).
// Throws lfcam::Error naming the file when it is not one.
DepthMap ReadDepthPng(const std::filesystem::path& path);
// The same from the file's bytes; `name` is for messages.
DepthMap DecodeDepthPng(std::span<const std::uint8_t> bytes, const std::string& name);
// The 8-bit confidence PNG's bytes, and reading it back into `map.confidence`.
std::string EncodeConfidencePng(const DepthMap& map);
void ReadConfidencePng(const std::filesystem::path& path, DepthMap& map);

// A picture for people: depth colour-mapped (turbo, near warm, far cool), unknown black, with a
// scale bar at the right labelled in the light field's length unit (WorldLengthUnit): metres for
// "mm", else the unit's own numbers and name ("units": the cameras' spacing taken as 1).
// CV_8UC3, R, G, B, upright.
cv::Mat DepthPreview(const DepthMap& map, const std::string& length_unit = "mm");

// Writes PATH (depth), its confidence and its preview, all or none; `length_unit` (WorldLengthUnit)
// goes into the depth PNG's chunk and the preview's scale.
void WriteDepthFiles(const std::filesystem::path& path, const DepthMap& map,
                     const std::string& extra_json = "{}", const std::string& length_unit = "mm");

}  // namespace lfcam
