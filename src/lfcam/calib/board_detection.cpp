#include "lfcam/calib/board_detection.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "lfcam/calib/charuco.h"

namespace lfcam {
namespace {

// Mean intensity of a small patch around `p` (clipped to the image).
double PatchMean(const cv::Mat& gray, cv::Point2f p, int radius) {
  const int x = int(std::lround(p.x)), y = int(std::lround(p.y));
  const cv::Rect patch = cv::Rect(x - radius, y - radius, 2 * radius + 1, 2 * radius + 1) &
                         cv::Rect(0, 0, gray.cols, gray.rows);
  if (patch.area() == 0) return 128.0;
  return cv::mean(gray(patch))[0];
}

}  // namespace

DetectionCopy MakeDetectionCopy(const cv::Mat& gray, const BoardDetectionOptions& options) {
  DetectionCopy copy{gray, 1.0};
  const int long_side = std::max(gray.cols, gray.rows);
  if (options.detect_long_side > 0 && long_side > options.detect_long_side) {
    copy.scale = double(options.detect_long_side) / long_side;
    cv::resize(gray, copy.image, cv::Size(), copy.scale, copy.scale, cv::INTER_AREA);
  }
  return copy;
}

int FoundCornerCount(const std::vector<cv::Point2f>& corners) {
  return int(std::count_if(corners.begin(), corners.end(), CornerFound));
}

std::optional<std::vector<cv::Point2f>> DetectBoard(const cv::Mat& gray, const BoardSpec& board,
                                                    const BoardDetectionOptions& options) {
  return board.charuco() ? DetectCharuco(gray, board, options)
                         : DetectChessboard(gray, board, options);
}

std::vector<cv::Point2f> OrderBoardCorners(const std::vector<cv::Point2f>& corners,
                                           const BoardSpec& board, const cv::Mat& gray) {
  const int cols = board.cols, rows = board.rows;
  std::vector<cv::Point2f> c = corners;
  auto at = [&](int i, int j) { return c[std::size_t(j * cols + i)]; };
  // Handedness: board x right and y up means, in image coordinates (y down), a negative cross
  // product of the x and y steps. A positive one is a mirrored numbering: flip the rows.
  const cv::Point2f ex = at(1, 0) - at(0, 0), ey = at(0, 1) - at(0, 0);
  if (ex.x * ey.y - ex.y * ey.x > 0) {
    std::vector<cv::Point2f> flipped(c.size());
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < cols; ++i)
        flipped[std::size_t(j * cols + i)] = c[std::size_t((rows - 1 - j) * cols + i)];
    c = flipped;
  }
  // Colour: the square diagonally outside corner (0, 0) is black and the one outside the last
  // corner is white (one count odd, one even); if not, the numbering is turned by 180 degrees.
  const cv::Point2f first = at(0, 0), last = at(cols - 1, rows - 1);
  const cv::Point2f outside_first = first - 0.5f * ((at(1, 0) - first) + (at(0, 1) - first));
  const cv::Point2f outside_last =
      last - 0.5f * ((at(cols - 2, rows - 1) - last) + (at(cols - 1, rows - 2) - last));
  const float step = std::min(cv::norm(at(1, 0) - first), cv::norm(at(0, 1) - first));
  const int radius = std::max(1, int(step * 0.15f));
  if (PatchMean(gray, outside_first, radius) > PatchMean(gray, outside_last, radius))
    std::reverse(c.begin(), c.end());
  return c;
}

std::optional<std::vector<cv::Point2f>> DetectChessboard(const cv::Mat& gray,
                                                         const BoardSpec& board,
                                                         const BoardDetectionOptions& options) {
  CV_Assert(gray.type() == CV_8UC1);
  const cv::Size pattern(board.cols, board.rows);
  const DetectionCopy copy = MakeDetectionCopy(gray, options);
  const cv::Mat& small = copy.image;
  std::vector<cv::Point2f> corners;
  bool found = cv::findChessboardCorners(small, pattern, corners, cv::CALIB_CB_FAST_CHECK);
  if (!found && options.thorough) {
    corners.clear();
    found = cv::findChessboardCorners(
        small, pattern, corners,
        cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_FAST_CHECK);
  }
  if (!found && options.thorough) {
    corners.clear();
    found = cv::findChessboardCornersSB(small, pattern, corners, cv::CALIB_CB_NORMALIZE_IMAGE);
  }
  if (!found || int(corners.size()) != board.corner_count()) return std::nullopt;
  for (auto& p : corners) p = copy.FullResolution(p);
  // Refine at full resolution, with a window well inside one square.
  double min_step = 1e30;
  for (int j = 0; j < board.rows; ++j)
    for (int i = 0; i + 1 < board.cols; ++i)
      min_step = std::min(min_step, double(cv::norm(corners[std::size_t(j * board.cols + i + 1)] -
                                                    corners[std::size_t(j * board.cols + i)])));
  const int half = std::clamp(int(min_step * 0.35), 2, 25);
  cv::cornerSubPix(gray, corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 50, 0.005));
  return OrderBoardCorners(corners, board, gray);
}

}  // namespace lfcam
