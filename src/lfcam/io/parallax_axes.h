#pragma once
// Whether a folder's views move the way their names say the cameras stand (docs/format.md,
// "The names' axes against the views' parallax").
//
// A grid's names say where each camera is, and conventions differ: a data set's row index or y
// coordinate may count up where lfcam reads it counting down. A rig whose rows run one way and
// columns the other is not a rig at all: no depth makes the views agree, and depth, the depth
// lookup and refocusing fail on it without a word. The views themselves say which way round
// they are: a point's parallax between the cameras left and right of the centre and between
// those below and above it are the same depth seen along two baselines. Measured per unit of
// baseline (a camera moved right sees a point move left in its image, one moved up sees it move
// down, by f / Z each), the two agree point for point, up to a constant each (shifted sensors),
// when the names' axes agree with each other; they are each other's negative when one axis runs
// the other way.
//
// What this cannot tell of a rectified rig: whether both axes run the other way (the whole rig
// turned half a turn about its axis: every view's parallax is then consistent, near and far
// exchanged), and which of two disagreeing axes is the wrong one. lfcam takes the columns as
// named (left to right is near-universal) and reverses the rows (whether a row index or y counts
// up or down is what conventions disagree on), and says so; then the occlusions tell the half turn
// (depth/occlusion_order.h). Parallel cameras (centred sensors)
// tell each axis apart: every point moves against its camera (f / Z > 0, no constant), so an
// axis along which the points move with the camera is reversed.
#include <filesystem>
#include <string>

#include "lfcam/io/grid_import.h"

namespace lfcam {

enum class AxesVerdict {
  kAgree,         // the views' parallax agrees with the names' axes
  kRowsReversed,  // along the rows and along the columns, it has opposite signs
  kColsReversed,  // parallel cameras only: along the rows, points move with the camera
  kBothReversed,  // parallel cameras only: along both, points move with the camera
  kSwapped,       // the views along a named row move vertically: rows and columns exchanged
  kUndecided,     // too few points, or too little depth in the scene, to tell
};

struct ParallaxAxes {
  AxesVerdict verdict = AxesVerdict::kUndecided;
  int points = 0;          // tracked from the centre view into all four views
  double correlation = 0;  // of the vertical against the horizontal parallax, point by point
  double cross = 0;        // of the vertical parallax against the row views' vertical motion
  double spread_px = 0;    // the horizontal parallax's spread over the points, px
  // The points' largest parallax (their 98th percentile) a grid step, either axis, px of the
  // views as read: for a rectified rig, how far from zero disparity the scene reaches.
  double largest_px_per_step = 0;
  // A single row or column of views, checked along it alone: the centre view against the
  // views two steps either side (no correlation: there is no second axis).
  bool single_line = false;
  std::string views;  // which views were compared, for the messages
  std::string why;    // undecided: why
};

// Reads the centre view of `grid` (a parallel rig's axes judged each on its own, a rectified
// rig's against each other) and the views up to two steps left and right of it in its row
// and below and above it in its column (from `dir`), tracks corners of the centre view into
// each (pyramidal Lucas-Kanade, kept where tracking back lands within 0.5 px), and compares.
// A single row or column of views is measured along it alone: its largest parallax, whether
// its views move across it (swapped: a column named as a row), and for parallel cameras
// whether its points move against the camera (otherwise undecided: a rectified rig's one axis
// has nothing to agree with). Undecided where a view is missing, fewer than 40 points track, or
// the scene's depth moves them by less than kMinSpreadPx. Throws lfcam::Error naming an
// unreadable view.
ParallaxAxes MeasureParallaxAxes(const std::filesystem::path& dir, const ImportedGrid& grid);

// The parallax's spread (px over the baseline compared) under which the axes are not judged.
inline constexpr double kMinSpreadPx = 0.5;

// `grid` with its rows (columns) taken in reverse: every view's y (x) negated and its row r made
// rows - 1 - r (its column c, cols - 1 - c).
ImportedGrid WithAxesReversed(const ImportedGrid& grid, bool rows, bool cols);

// `grid` with its rows and columns exchanged, as if the names' two indices (or two numbers) were
// swapped: the view named at row i from the top and column j from the left taken as row j and
// column i; in positions, (x, y) becomes (-y, -x).
ImportedGrid WithAxesSwapped(const ImportedGrid& grid);

// The verdict in a word ("agree", "rows-reversed", "cols-reversed", "both-reversed", "swapped",
// "undecided"), and in words, for
// the import's notes.
std::string ToString(AxesVerdict verdict);
std::string Describe(const ParallaxAxes& axes);

}  // namespace lfcam
