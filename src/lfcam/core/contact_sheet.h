#pragma once
// A contact sheet: images in a grid, each labelled, under a title (the demo's sequences).
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace lfcam {

struct ContactSheetOptions {
  int columns = 0;       // 0: all in one row, up to 6 a row
  int tile_width = 256;  // each image is scaled to this width
  std::string title;
};

// Images are 8-bit sRGB RGB (CV_8UC3); labels may be fewer than images.
cv::Mat MakeContactSheet(const std::vector<cv::Mat>& images, const std::vector<std::string>& labels,
                         const ContactSheetOptions& options);

}  // namespace lfcam
