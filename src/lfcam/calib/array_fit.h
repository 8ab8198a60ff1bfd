#pragma once
// The paper's array fit (§5.2.2 and its appendix), made precise: a least-squares plane through
// the camera centres, the centres projected onto it, a 2D frame from their barycentre and the
// projected world x axis, and the rigid motion (alpha*, beta*, theta*) that best fits the ideal
// grid of cell centres P(row, col) = (pitch (col - (cols-1)/2), pitch (row - (rows-1)/2)) to
// them. The result is the PRP window: p_ca, u_ca, v_ca, n_ca.
//
// theta* maximises C cos(theta) + S sin(theta), with, over the cameras (q the projected centre in
// the 2D frame less the barycentre offset, P the ideal cell centre),
//   C = sum (q_x P_x + q_y P_y),   S = sum (q_y P_x - q_x P_y),
// i.e. it solves f(theta) = S cos(theta) - C sin(theta) = 0. The paper finds it by
// Newton-Raphson from theta = 0; the closed form atan2(S, C) cross-checks it.
#include <vector>

#include "lfcam/core/slab.h"

namespace lfcam {

struct GridCamera {
  int row = 0, col = 0;
  Vec3 center;  // world, mm
};

struct ArrayFit {
  ArrayPlane array;            // the PRP window (p_ca, u_ca, v_ca, n_ca) and its grid
  Vec3 plane_normal;           // unit, = n_ca
  Vec3 barycentre;             // of the centres, world
  double plane_rms_mm = 0;     // distance of the centres from the plane, RMS
  double alpha = 0, beta = 0;  // mm, in the 2D frame
  double theta_newton = 0, theta_closed = 0;  // radians
  int newton_iterations = 0;
  double grid_rms_mm = 0;  // projected centre to its ideal cell centre, RMS
  // Per camera, in the order given: the ideal cell centre (world) and the distance to it.
  std::vector<Vec3> ideal_centers;
  std::vector<double> distance_to_ideal_mm;
};

// How the array's grid, as numbered (row 0 at the bottom, column 0 at the left, seen from behind
// the array), runs in the world board's frame: the directions in which the camera centres move
// as the column and the row grow (a least-squares fit centre = a + col u + row v), against the
// board's x and y. A world board hung the other way up (its bottom-left square, seen from the
// array, white) numbers its corners from the other end: the grid then runs half a turn against
// it.
enum class GridTurn { kAligned, kHalfTurn, kQuarterTurn, kMirrored };
struct GridOrientation {
  GridTurn turn = GridTurn::kAligned;
  double angle_deg = 0;  // of the grid's columns against the board's x, in the board's plane
};
// Needs two distinct rows or columns among `cameras`; kAligned otherwise.
GridOrientation GridAgainstBoard(const std::vector<GridCamera>& cameras);

// Fits the array. `scene_side` is any point on the scene's side of the array (the world board's
// centre, say): n_ca is turned to point away from it. Throws lfcam::Error when fewer than three
// cameras are given or their centres do not span a plane (all on a line), naming the cameras.
ArrayFit FitArray(const std::vector<GridCamera>& cameras, int rows, int cols, double pitch_mm,
                  const Vec3& scene_side);

}  // namespace lfcam
