#pragma once
// Finding a chessboard's inner corners in a photograph: detected on a downscaled copy (fast),
// refined at full resolution (accurate), and put in the board's own point order
// (calib/board.h), so that every camera numbers the corners of a shared board pose alike.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "lfcam/calib/board.h"

namespace lfcam {

struct BoardDetectionOptions {
  int detect_long_side = 1024;  // the downscaled copy's longer side (0: detect at full size)
  // false: OpenCV's plain detector only (about 10 ms; gives up fast on a board partly out of
  // view). true: also adaptive thresholds and the sector-based detector (up to a second or two
  // on an image without the whole board), for images the plain one missed but that should
  // hold the board.
  bool thorough = false;
};

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
