#pragma once
// Disparity as the light field depth benchmarks count it (the HCI 4D Light Field Benchmark's
// convention, docs/depth.md): the shift, in st samples (a rectified rig's pixels), of a scene
// point between neighbouring views, positive nearer than the st-plane (the zero-disparity plane)
// and negative beyond it. For a point at depth Z from the array's plane, a view at depth Z_c on
// it, an st-plane Z0 from the view and samples ds mm apart on it, cameras a pitch p apart:
//   d = p / ds * (Z0 / (Z - Z_c) - 1).
// A point in the centre view at pixel (x, y) with disparity d appears in the view (dr, dc) grid
// steps away at (x - d dc, y + d dr) (x right, y down; rows counted up, as lfcam counts them).
//
// Written as the benchmark's PFM: "Pf", width and height, a negative scale (little-endian
// float32), rows from the bottom of the image up, as its evaluation toolkit reads it.
#include <filesystem>
#include <opencv2/core.hpp>

#include "lfcam/core/lightfield.h"
#include "lfcam/depth/depth_map.h"

namespace lfcam {

// The disparity of every sample of `map` (its view of `lf`), in the map's layout (row l = st row
// l, bottom-up); NaN where the depth is unknown or not in front of the view.
cv::Mat DisparityOf(const LightField& lf, const DepthMap& map);

// Writes a CV_32FC1 disparity (bottom-up rows, as DisparityOf gives it) as a PFM, atomically;
// unknown samples (NaN) are written as 0, the zero-disparity plane. Returns how many were.
// Throws lfcam::Error naming the file.
int WriteDisparityPfm(const std::filesystem::path& path, const cv::Mat& disparity);

}  // namespace lfcam
