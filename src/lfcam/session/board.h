#pragma once
// A calibration board: a plain chessboard, sized OpenCV's way by its inner corners, or a ChArUco
// board (OpenCV's aruco module: a chessboard with an ArUco marker in every white square, so that
// each corner is identified even when only part of the board is in view; calib/charuco.h).
//
// Board frame (docs/conventions.md): origin at the bottom-left outer corner of the squared area
// as seen from the cameras, x along its bottom edge, y up its left edge, z toward the cameras
// (the world frame is the world board's). The bottom-left square is black. Inner corner (i, j),
// i = 0 .. cols-1 along x and j = 0 .. rows-1 along y, sits at ((i + 1) square, (j + 1) square)
// and is point number j * cols + i (OpenCV's row-major order, rows counted from the bottom).
// One odd and one even count make a chessboard's orientation unambiguous; a ChArUco board's
// markers identify it whatever the counts. A ChArUco board is OpenCV's own layout (its markers,
// their ids, which squares are black), put in this frame: OpenCV 4.6 numbers the board from its
// top-left with y down, so its corner id k is point (rows - 1 - k / cols) * cols + k % cols here.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "lfcam/core/geometry.h"

namespace lfcam {

enum class BoardKind { kChessboard, kCharuco };

struct BoardSpec {
  BoardSpec() = default;
  // A chessboard.
  BoardSpec(int inner_cols, int inner_rows, double square)
      : cols(inner_cols), rows(inner_rows), square_mm(square) {}

  int cols = 0, rows = 0;  // inner corners along x and y
  double square_mm = 0;
  BoardKind kind = BoardKind::kChessboard;
  double marker_mm = 0;    // ChArUco: the side of a marker, its black border included
  std::string dictionary;  // ChArUco: OpenCV's predefined dictionary, for example "5X5_100"

  // The squared area's size (cols + 1 by rows + 1 squares).
  double width_mm() const { return (cols + 1) * square_mm; }
  double height_mm() const { return (rows + 1) * square_mm; }
  int corner_count() const { return cols * rows; }
  Vec3 corner(int i, int j) const { return {(i + 1) * square_mm, (j + 1) * square_mm, 0.0}; }
  std::vector<Vec3> corners() const;  // in point order
  bool charuco() const { return kind == BoardKind::kCharuco; }
  // Chessboard: whether the square containing board point (x, y) (mm, in the squared area) is
  // black.
  bool black_at(double x, double y) const;
  // "COLSxROWS@MM" or "charuco:SQUARES_XxSQUARES_Y@MM/MARKER_MM:DICTIONARY", the form flags and
  // manifests use.
  std::string spec() const;
  bool operator==(const BoardSpec&) const = default;
};

// Parses "COLSxROWS@MM" (for example "10x7@30"): 2..200 inner corners a side, one count odd
// and the other even, a square of 0.1..10000 mm. Or, for a ChArUco board, OpenCV's own way of
// sizing it, by squares: "charuco:SXxSY@SQUARE/MARKER[:DICTIONARY]" (for example
// "charuco:11x9@30/22", which has 10x8 inner corners; the dictionary defaults to 5X5_100 and
// must hold a marker for every white square). Throws lfcam::Error saying what is wrong.
BoardSpec ParseBoardSpec(const std::string& text);

// {"type": "chessboard", "spec": "10x7@30", "inner_corners": [10, 7], "square_mm": 30}, and for
// ChArUco {"type": "charuco", ..., "squares": [11, 8], "marker_mm": 22, "dictionary": "5X5_100"}.
nlohmann::json BoardToJson(const BoardSpec& board);
BoardSpec BoardFromJson(const nlohmann::json& j, const std::string& where);

}  // namespace lfcam
