#pragma once
// A calibration board held in front of a scene, rendered analytically: each pixel gets the exact
// share of black and white under its footprint, approximated by the board-aligned rectangle
// with the footprint's extent along the board's axes (the box filter's integral of a checker is
// separable: a triangle wave per axis; a ChArUco board's marker cells are rectangles too,
// calib/charuco.h), widened for the lens's blur to the box of the same variance. No
// supersampling, and corners stay where they are.
#include "lfcam/session/board.h"
#include "lfcam/sim/camera_module.h"
#include "lfcam/sim/scene.h"

namespace lfcam {

struct BoardAppearance {
  double white = 0.80, black = 0.03;  // linear albedo times illumination
  double margin_squares = 1.0;        // the white border around the squared area, in squares
};

// The share of the rectangle [x0, x1] x [y0, y1] (board mm) that is black squares (a
// chessboard).
double BlackAreaFraction(const BoardSpec& board, double x0, double x1, double y0, double y1);

// Pixel radiance of `board` at `world_from_board` before `scene`, which shows where the board is
// not: the pixel's `behind` value when given, else one ray per pixel.
PixelRadiance BoardInFrontOf(const BoardSpec& board, const Rigid3& world_from_board,
                             const Scene& scene, const BoardAppearance& appearance = {});

// The pixels of `module` whose footprint may reach `board` (with its margin) at
// `world_from_board`, a run of columns a row: outside them BoardInFrontOf gives what stands
// behind. Conservative: the rays of every 8th pixel are traced and each stretch between two is
// kept when the board, grown by the stretch's extent on its plane, meets it.
PixelRuns BoardFootprintRuns(const BoardSpec& board, const Rigid3& world_from_board,
                             const SimulatedModule& module, const cv::Mat& directions,
                             const BoardAppearance& appearance = {});

// Pixel radiance of `scene` alone, the mean of n x n rays over the pixel footprint seen through
// the lens (the pixel's box convolved with the lens's point spread), one drawn in each of its
// n x n strata of equal weight (the same draw at every shot of a pixel). n = 1: the pixel's centre
// ray, no blur.
PixelRadiance SceneRadiance(const Scene& scene, int supersampling);

}  // namespace lfcam
