#pragma once
// ChArUco boards through OpenCV's aruco module (opencv_contrib): the board's layout in lfcam's
// board frame (session/board.h), which the simulator draws, and the detector that finds its
// corners, each identified by the markers around it, even when only part of the board is in view.
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "lfcam/calib/board_detection.h"
#include "lfcam/session/board.h"

namespace lfcam {

struct CharucoMarker {
  int id = 0;
  double x0 = 0, y0 = 0;            // the marker's bottom-left corner, board mm
  double side = 0;                  // mm, its black border included
  int cells = 0;                    // cells a side, the border included (the dictionary's bits + 2)
  std::vector<std::uint8_t> black;  // cells x cells, row 0 at the top (largest y); 1 = black
};

struct CharucoLayout {
  BoardSpec board;
  std::vector<CharucoMarker> markers;
  std::vector<int> marker_in_square;  // square (i, j) at j * (cols + 1) + i: a marker, or -1
  // A square without a marker is black.
  int marker_at(int i, int j) const {
    return marker_in_square[std::size_t(j * (board.cols + 1) + i)];
  }
};

// OpenCV's layout of `board` (which must be a ChArUco board).
CharucoLayout MakeCharucoLayout(const BoardSpec& board);

// The share of the rectangle [x0, x1] x [y0, y1] (board mm) that is black: squares and marker
// cells, each an exact rectangle overlap.
double CharucoBlackAreaFraction(const CharucoLayout& layout, double x0, double x1, double y0,
                                double y1);

// The corners of ChArUco `board` found in `gray` (CV_8UC1, full resolution), in the board's point
// order, NaN where a corner was not found; nullopt when fewer than `options.min_partial_corners`
// were found or they all lie on one row or column of the board. Markers are found on the
// downscaled copy; corners are interpolated from them and refined at full resolution.
std::optional<std::vector<cv::Point2f>> DetectCharuco(const cv::Mat& gray, const BoardSpec& board,
                                                      const BoardDetectionOptions& options = {});

}  // namespace lfcam
