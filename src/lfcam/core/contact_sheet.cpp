#include "lfcam/core/contact_sheet.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"

namespace lfcam {

cv::Mat MakeContactSheet(const std::vector<cv::Mat>& images, const std::vector<std::string>& labels,
                         const ContactSheetOptions& options) {
  if (images.empty()) throw Error("contact sheet: no images");
  if (options.tile_width < 1 || options.tile_width > kMaxImageSide || options.columns < 0)
    throw Error(fmt::format("contact sheet: tile width {} must be 1..{} and columns {} >= 0",
                            options.tile_width, kMaxImageSide, options.columns));
  const int n = int(images.size());
  const int columns = options.columns > 0 ? std::min(options.columns, n) : std::min(n, 6);
  const int rows = (n + columns - 1) / columns;
  const int tile_w = std::max(16, options.tile_width);
  constexpr int kGap = 8, kLabelH = 24;
  const int title_h = options.title.empty() ? 0 : 36;
  // Sizes in double first: nothing wraps, and a sheet too large is refused before allocation.
  double tile_h_exact = 0;
  for (const auto& image : images)
    tile_h_exact = std::max(tile_h_exact, std::round(double(image.rows) * tile_w / image.cols));
  const double sheet_w = double(columns) * (tile_w + kGap) + kGap;
  const double sheet_h = title_h + double(rows) * (tile_h_exact + kLabelH + kGap) + kGap;
  if (sheet_w > kMaxImageSide || sheet_h > kMaxImageSide)
    throw Error(
        fmt::format("contact sheet: {:.0f}x{:.0f} pixels is larger than the limit of {} "
                    "a side (use a smaller tile width or fewer columns)",
                    sheet_w, sheet_h, kMaxImageSide));
  RequireMemory(sheet_w * sheet_h * 3 * 2, "the contact sheet");
  const int tile_h = int(tile_h_exact);
  const cv::Scalar background(24, 24, 24), ink(235, 235, 235);
  cv::Mat sheet(title_h + rows * (tile_h + kLabelH + kGap) + kGap, columns * (tile_w + kGap) + kGap,
                CV_8UC3, background);
  if (title_h)
    cv::putText(sheet, options.title, {kGap, 26}, cv::FONT_HERSHEY_SIMPLEX, 0.7, ink, 1,
                cv::LINE_AA);
  for (int index = 0; index < n; ++index) {
    const cv::Mat& image = images[std::size_t(index)];
    if (image.type() != CV_8UC3) throw Error("contact sheet: images must be 8-bit RGB");
    const int x = kGap + (index % columns) * (tile_w + kGap);
    const int y = title_h + kGap + (index / columns) * (tile_h + kLabelH + kGap);
    cv::Mat tile;
    const int h = int(std::lround(double(image.rows) * tile_w / image.cols));
    cv::resize(image, tile, {tile_w, h}, 0, 0, cv::INTER_AREA);
    tile.copyTo(sheet(cv::Rect(x, y, tile_w, h)));
    if (std::size_t(index) < labels.size())
      cv::putText(sheet, labels[std::size_t(index)], {x, y + tile_h + 17}, cv::FONT_HERSHEY_SIMPLEX,
                  0.45, ink, 1, cv::LINE_AA);
  }
  return sheet;
}

}  // namespace lfcam
