#pragma once
// The HCI 4D Light Field Benchmark's `parameters.cfg` (Honauer et al., ACCV 2016): an INI file
// beside the views (input_Cam000.png ...) that gives the rig's metric geometry. lfcam reads:
//
//   [intrinsics]  focal_length_mm, image_resolution_x_px, image_resolution_y_px,
//                 sensor_size_mm (across the larger image side)
//   [extrinsics]  num_cams_x, num_cams_y, baseline_mm (between neighbours),
//                 focus_distance_m (the zero-disparity plane's distance)
//   [meta]        disp_min, disp_max (optional: the scene's disparity range, px)
//
// Other keys and sections are kept as text (the `meta` of the import) and otherwise ignored.
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace lfcam {

struct HciParameters {
  double focal_length_mm = 0;
  int width_px = 0, height_px = 0;
  double sensor_size_mm = 0;
  int cams_x = 0, cams_y = 0;
  double baseline_mm = 0;
  double focus_distance_mm = 0;
  std::optional<double> disp_min, disp_max;
  std::map<std::string, std::string> values;  // every "section.key" as written

  // The focal length in pixels: focal_length_mm * max(width, height) / sensor_size_mm.
  double focal_px() const;
  // The depth (mm, from the camera plane) of disparity d (px between neighbours), and back:
  //   depth = baseline * focal_px * focus / (d * focus + baseline * focal_px).
  double DepthOfDisparity(double disparity_px) const;
  double DisparityOfDepth(double depth_mm) const;
};

// Parses the text of a parameters.cfg; throws lfcam::Error naming `where`, the line and the key
// (a line that is neither a section, a key = value nor a comment; a required key missing, not a
// number, or out of range).
HciParameters ParseHciParameters(std::string_view text, const std::string& where);

}  // namespace lfcam
