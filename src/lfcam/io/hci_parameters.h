#pragma once
// The HCI 4D Light Field Benchmark's `parameters.cfg` (Honauer et al., ACCV 2016): an INI file
// beside the views (input_Cam000.png ...) that gives the rig's metric geometry. lfcam reads:
//
//   [intrinsics]  focal_length_mm, image_resolution_x_px, image_resolution_y_px,
//                 sensor_size_mm (across the larger image side)
//   [extrinsics]  num_cams_x, num_cams_y, baseline_mm (between neighbours),
//                 focus_distance_m (the zero-disparity plane's distance)
//   [meta]        disp_min, disp_max (the scene's disparity range, px)
//
// The benchmark's own files give every key. Folders made elsewhere in its format often give only
// some (the grid, the image size and the disparity range), so every key is optional, and the
// import assumes what is missing and says so, as it does without the file. Keys that only mean
// something together come together or not at all: the image's two sides, the grid's two counts,
// focal_length_mm with sensor_size_mm and the image size, and focus_distance_m with baseline_mm
// (a distance in millimetres beside cameras spaced in assumed units would mean nothing).
//
// Other keys and sections are kept as text (the `meta` of the import) and otherwise ignored.
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace lfcam {

struct HciParameters {
  std::optional<double> focal_length_mm, sensor_size_mm;
  std::optional<int> width_px, height_px;
  std::optional<int> cams_x, cams_y;
  std::optional<double> baseline_mm;
  std::optional<double> focus_distance_mm;
  std::optional<double> disp_min, disp_max;
  std::map<std::string, std::string> values;  // every "section.key" as written
  std::string source;                         // where it was read from (for messages)

  // The focal length in pixels, focal_length_mm * max(width, height) / sensor_size_mm, where the
  // file gives them.
  std::optional<double> focal_px() const;
  // Whether the file gives the rig's metric geometry: the focal length, the baseline and the
  // focus distance.
  bool metric() const { return focal_px() && baseline_mm && focus_distance_mm; }
  // Of a metric rig: the depth (mm, from the camera plane) of disparity d (px between
  // neighbours), and back:
  //   depth = baseline * focal_px * focus / (d * focus + baseline * focal_px).
  double DepthOfDisparity(double disparity_px) const;
  double DisparityOfDepth(double depth_mm) const;
};

// Parses the text of a parameters.cfg; throws lfcam::Error naming `where`, the line and the key
// (a line that is neither a section, a key = value nor a comment; a key not a number or out of
// range; a key given without those it goes with).
HciParameters ParseHciParameters(std::string_view text, const std::string& where);

}  // namespace lfcam
