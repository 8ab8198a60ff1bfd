#pragma once
// Finding a board's inner corners in a photograph: detected on a downscaled copy (fast), refined
// at full resolution (accurate), and put in the board's own point order (session/board.h), so that
// every camera numbers the corners of a shared board pose alike. A chessboard is found whole or
// not at all; a ChArUco board (calib/charuco.h) also in part, its missing corners NaN.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "lfcam/session/board.h"

namespace lfcam {

struct BoardDetectionOptions {
  int detect_long_side = 1024;  // the downscaled copy's longer side (0: detect at full size)
  // false: OpenCV's plain detector only (about 10 ms; gives up fast on a board partly out of
  // view). true: also adaptive thresholds and the sector-based detector (up to a second or two
  // on an image without the whole board), for images the plain one missed but that should
  // hold the board.
  bool thorough = false;
  // ChArUco: a view needs at least this many corners (or the whole board, if it has fewer).
  int min_partial_corners = 8;
};

// The copy boards are searched on: `gray` scaled so that its longer side is at most
// `options.detect_long_side`, and the scale used (1 when not reduced).
struct DetectionCopy {
  cv::Mat image;
  double scale = 1.0;
  // A point found in the copy, in the full-resolution image's pixels.
  cv::Point2f FullResolution(cv::Point2f p) const {
    return (p + cv::Point2f(0.5f, 0.5f)) * float(1.0 / scale) - cv::Point2f(0.5f, 0.5f);
  }
};
DetectionCopy MakeDetectionCopy(const cv::Mat& gray, const BoardDetectionOptions& options);

// Whether a detected corner is there (a partial ChArUco view has NaN for the ones not found).
inline bool CornerFound(const cv::Point2f& p) { return p.x == p.x && p.y == p.y; }
int FoundCornerCount(const std::vector<cv::Point2f>& corners);

// The corners of `board` (either kind) in `gray`: DetectChessboard or DetectCharuco.
std::optional<std::vector<cv::Point2f>> DetectBoard(const cv::Mat& gray, const BoardSpec& board,
                                                    const BoardDetectionOptions& options = {});

// The corners of `board` in `gray` (CV_8UC1, full resolution) in the board's point order, or
// nullopt when the whole board is not found. The board must be seen from its front.
std::optional<std::vector<cv::Point2f>> DetectChessboard(const cv::Mat& gray,
                                                         const BoardSpec& board,
                                                         const BoardDetectionOptions& options = {});

// Puts corners found in OpenCV's row-major order (cols per row) into the board's order: the
// board's x runs right and its y up in the image (a board seen from the front), and the square
// diagonally outside corner 0 is black. `gray` is sampled to tell black from white.
std::vector<cv::Point2f> OrderBoardCorners(const std::vector<cv::Point2f>& corners,
                                           const BoardSpec& board, const cv::Mat& gray);

}  // namespace lfcam
