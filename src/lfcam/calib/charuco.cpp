#include "lfcam/calib/charuco.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

// OpenCV's predefined dictionary "NxN_COUNT": DICT_4X4_50 is 0, then 100, 250, 1000, then 5X5.
cv::Ptr<cv::aruco::Dictionary> Dictionary(const std::string& name) {
  for (int bits = 4; bits <= 7; ++bits) {
    int k = 0;
    for (int count : {50, 100, 250, 1000}) {
      if (name == fmt::format("{}X{}_{}", bits, bits, count))
        return cv::aruco::getPredefinedDictionary((bits - 4) * 4 + k);
      ++k;
    }
  }
  throw Error(fmt::format("'{}' is not one of OpenCV's ArUco dictionaries", name));
}

cv::Ptr<cv::aruco::CharucoBoard> OpenCvBoard(const BoardSpec& board) {
  if (!board.charuco()) throw Error(fmt::format("board {} is not a ChArUco board", board.spec()));
  return cv::aruco::CharucoBoard::create(board.cols + 1, board.rows + 1, float(board.square_mm),
                                         float(board.marker_mm), Dictionary(board.dictionary));
}

// The length of [a0, a1] inside [b0, b1].
double Overlap(double a0, double a1, double b0, double b1) {
  return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
}

}  // namespace

CharucoLayout MakeCharucoLayout(const BoardSpec& board) {
  const auto cv_board = OpenCvBoard(board);
  const auto& dictionary = *cv_board->dictionary;
  CharucoLayout layout;
  layout.board = board;
  layout.marker_in_square.assign(std::size_t(board.cols + 1) * std::size_t(board.rows + 1), -1);
  const double height = board.height_mm();
  for (std::size_t m = 0; m < cv_board->ids.size(); ++m) {
    // OpenCV's board frame has its origin at the top-left and y down; corner 0 of a marker is
    // its top-left (the first row of its bits).
    const auto& corners = cv_board->objPoints[m];
    float x_min = corners[0].x, y_min = corners[0].y;
    for (const auto& c : corners) {
      x_min = std::min(x_min, c.x);
      y_min = std::min(y_min, c.y);
    }
    CharucoMarker marker;
    marker.id = cv_board->ids[m];
    marker.side = board.marker_mm;
    marker.x0 = x_min;
    marker.y0 = height - y_min - board.marker_mm;
    marker.cells = dictionary.markerSize + 2;
    const cv::Mat bits = cv::aruco::Dictionary::getBitsFromByteList(
        dictionary.bytesList.rowRange(marker.id, marker.id + 1), dictionary.markerSize);
    marker.black.assign(std::size_t(marker.cells * marker.cells), 1);  // the border
    for (int r = 0; r < dictionary.markerSize; ++r)
      for (int c = 0; c < dictionary.markerSize; ++c)
        marker.black[std::size_t((r + 1) * marker.cells + c + 1)] = bits.at<uchar>(r, c) ? 0 : 1;
    const int i = int(std::floor((marker.x0 + 0.5 * marker.side) / board.square_mm));
    const int j = int(std::floor((marker.y0 + 0.5 * marker.side) / board.square_mm));
    layout.marker_in_square[std::size_t(j * (board.cols + 1) + i)] = int(layout.markers.size());
    layout.markers.push_back(std::move(marker));
  }
  return layout;
}

double CharucoBlackAreaFraction(const CharucoLayout& layout, double x0, double x1, double y0,
                                double y1) {
  const BoardSpec& b = layout.board;
  const double area = (x1 - x0) * (y1 - y0);
  const double s = b.square_mm;
  const int squares_x = b.cols + 1, squares_y = b.rows + 1;
  if (!(area > 0)) {  // a point
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    x0 = x1 = cx;
    y0 = y1 = cy;
  }
  const int i0 = std::max(0, int(std::floor(x0 / s)));
  const int i1 = std::min(squares_x - 1, int(std::floor(x1 / s)));
  const int j0 = std::max(0, int(std::floor(y0 / s)));
  const int j1 = std::min(squares_y - 1, int(std::floor(y1 / s)));
  double black = 0;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const int m = layout.marker_at(i, j);
      if (!(area > 0)) {  // the value at the point
        if (m < 0) return 1.0;
        const CharucoMarker& k = layout.markers[std::size_t(m)];
        const double cell = k.side / k.cells;
        const int c = int(std::floor((x0 - k.x0) / cell));
        const int r = k.cells - 1 - int(std::floor((y0 - k.y0) / cell));
        if (c < 0 || r < 0 || c >= k.cells || r >= k.cells) return 0.0;
        return k.black[std::size_t(r * k.cells + c)];
      }
      const double ox = Overlap(x0, x1, i * s, (i + 1) * s);
      const double oy = Overlap(y0, y1, j * s, (j + 1) * s);
      if (ox * oy <= 0) continue;
      if (m < 0) {
        black += ox * oy;
        continue;
      }
      const CharucoMarker& k = layout.markers[std::size_t(m)];
      const double cell = k.side / k.cells;
      for (int r = 0; r < k.cells; ++r) {
        const double top = k.y0 + (k.cells - r) * cell;
        const double cy = Overlap(y0, y1, top - cell, top);
        if (cy <= 0) continue;
        for (int c = 0; c < k.cells; ++c)
          if (k.black[std::size_t(r * k.cells + c)])
            black += cy * Overlap(x0, x1, k.x0 + c * cell, k.x0 + (c + 1) * cell);
      }
    }
  if (!(area > 0)) return 0.0;  // outside the squared area
  return black / area;
}

std::optional<std::vector<cv::Point2f>> DetectCharuco(const cv::Mat& gray, const BoardSpec& board,
                                                      const BoardDetectionOptions& options) {
  CV_Assert(gray.type() == CV_8UC1);
  const auto cv_board = OpenCvBoard(board);
  const DetectionCopy copy = MakeDetectionCopy(gray, options);
  auto parameters = cv::aruco::DetectorParameters::create();
  if (options.thorough) {
    // More threshold windows, smaller markers.
    parameters->adaptiveThreshWinSizeMax = 53;
    parameters->adaptiveThreshWinSizeStep = 4;
    parameters->minMarkerPerimeterRate = 0.01;
  }
  std::vector<std::vector<cv::Point2f>> markers;
  std::vector<int> ids;
  cv::aruco::detectMarkers(copy.image, cv_board->dictionary, markers, ids, parameters);
  if (ids.empty()) return std::nullopt;
  for (auto& marker : markers)
    for (auto& p : marker) p = copy.FullResolution(p);
  std::vector<cv::Point2f> found;
  std::vector<int> found_ids;
  cv::aruco::interpolateCornersCharuco(markers, ids, gray, cv_board, found, found_ids);
  if (found.empty()) return std::nullopt;
  // Refine at full resolution, with a window that stays clear of the markers' edges (the
  // interpolation's own refinement leaves the corners several tenths of a pixel off).
  double side = 0;
  for (const auto& marker : markers)
    side += cv::norm(marker[1] - marker[0]) / double(markers.size());
  const double gap_px = side * 0.5 * (board.square_mm - board.marker_mm) / board.marker_mm;
  const int half = std::clamp(int(gap_px * 0.8), 2, 25);
  cv::cornerSubPix(gray, found, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 50, 0.005));
  // Into the board's point order (session/board.h), NaN where not found.
  const int cols = board.cols, rows = board.rows;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<cv::Point2f> corners(std::size_t(board.corner_count()), cv::Point2f(nan, nan));
  std::set<int> columns, lines;
  for (std::size_t k = 0; k < found_ids.size(); ++k) {
    const int id = found_ids[k];
    if (id < 0 || id >= board.corner_count()) continue;
    const int i = id % cols, j = rows - 1 - id / cols;
    corners[std::size_t(j * cols + i)] = found[k];
    columns.insert(i);
    lines.insert(j);
  }
  const int count = int(columns.empty() ? 0 : found_ids.size());
  if (count < std::min(options.min_partial_corners, board.corner_count()) || columns.size() < 2 ||
      lines.size() < 2)
    return std::nullopt;
  return corners;
}

}  // namespace lfcam
