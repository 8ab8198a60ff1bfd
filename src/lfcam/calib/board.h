#pragma once
// A calibration board: a plain chessboard, sized OpenCV's way by its inner corners.
//
// Board frame (docs/conventions.md): origin at the bottom-left outer corner of the squared area
// as seen from the cameras, x along its bottom edge, y up its left edge, z toward the cameras
// (the world frame is the world board's). The bottom-left square is black. Inner corner (i, j),
// i = 0 .. cols-1 along x and j = 0 .. rows-1 along y, sits at ((i + 1) square, (j + 1) square)
// and is point number j * cols + i (OpenCV's row-major order, rows counted from the bottom).
// One odd and one even count make the board's orientation unambiguous.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "lfcam/core/geometry.h"

namespace lfcam {

struct BoardSpec {
  int cols = 0, rows = 0;  // inner corners along x and y
  double square_mm = 0;

  // The squared area's size (cols + 1 by rows + 1 squares).
  double width_mm() const { return (cols + 1) * square_mm; }
  double height_mm() const { return (rows + 1) * square_mm; }
  int corner_count() const { return cols * rows; }
  Vec3 corner(int i, int j) const { return {(i + 1) * square_mm, (j + 1) * square_mm, 0.0}; }
  std::vector<Vec3> corners() const;  // in point order
  // Whether the square containing board point (x, y) (mm, in the squared area) is black.
  bool black_at(double x, double y) const;
  // "COLSxROWS@MM", the form flags and manifests use.
  std::string spec() const;
  bool operator==(const BoardSpec&) const = default;
};

// Parses "COLSxROWS@MM" (for example "10x7@30"): 2..200 inner corners a side, one count odd
// and the other even, a square of 0.1..10000 mm. Throws lfcam::Error saying what is wrong.
BoardSpec ParseBoardSpec(const std::string& text);

// {"type": "chessboard", "spec": "10x7@30", "inner_corners": [10, 7], "square_mm": 30}.
nlohmann::json BoardToJson(const BoardSpec& board);
BoardSpec BoardFromJson(const nlohmann::json& j, const std::string& where);

}  // namespace lfcam
