#pragma once
// Which way round a rectified rig's depth runs, told by its occlusions (docs/format.md, "Near and
// far, from the occlusions").
//
// A rectified rig's views agree with a depth whether its cameras stand as named or the whole rig
// is turned half a turn about its axis (every position negated): each point's parallax changes
// sign, and with it which side of the zero-disparity plane the point lies, near and far
// exchanged. The Stanford archive's positions are parallax "up to an unknown scale and
// translation" (whose sign differs between its data sets), and a plenoptic camera's views come
// with indices whose direction is a convention. Parallax alone cannot tell; occlusions can. At a
// depth edge, a view whose camera stands so that the near surface slides over the far one (a
// "closing" view) does not see the far side's samples next to the edge; one on the other side (an
// "opening" view) sees both sides. So beside a true edge, the far side's samples match worse in
// the closing views than in the opening ones, and the near side's match alike in both. Read with
// the rig turned half a turn, the map is the same but near and far are exchanged, and so are the
// closing and opening views: the mismatch then lies on the side the reading calls near.
//
// Measured on the central view (views of 1024 samples a side or more first reduced to 512-1023):
// its depth (the plane sweep at reach 2 without the silhouettes' visibility step, the one step
// that assumes which side is near), every pair of neighbouring samples whose depths move them two
// samples or more apart in some view and whose sides each go on at their depth for four samples
// (a jump, not a slope or an island) and are confident, and each side's two samples next to the
// edge, read at their own depth in every view within reach 4 that moves them that far apart.
#include <string>

#include "lfcam/core/lightfield.h"

namespace lfcam {

enum class OcclusionVerdict {
  kAsNamed,    // the occluded sides are the far ones: the rig stands as its names say
  kReversed,   // they are the near ones: the rig turned half a turn, near and far exchanged
  kUndecided,  // too few depth edges, or no clear majority
};

struct OcclusionOrder {
  OcclusionVerdict verdict = OcclusionVerdict::kUndecided;
  int as_named = 0;  // depth edges whose far side matches worse in the closing views
  int reversed = 0;  // whose near side does
  double seconds = 0;
  std::string why;  // undecided: why
};

// At least this many depth edges that vote, and this share of them one way, decide.
inline constexpr int kFewestOcclusionVotes = 40;
inline constexpr double kOcclusionMajority = 0.6;

// Measures `lf`'s central view as above. Undecided (with `why`) for a single view, a view warped
// by a homography (the st-plane not parallel to the array), or too few or split votes.
OcclusionOrder MeasureOcclusionOrder(const LightField& lf);

// `lf` with its views' samples taken half a turn round the grid: view (r, c) holds what view
// (rows - 1 - r, cols - 1 - c) held, the geometry kept (tests, and the check's counter-example).
LightField WithViewsTurnedHalfATurn(const LightField& lf);

std::string ToString(OcclusionVerdict verdict);  // "as-named", "reversed", "undecided"
std::string Describe(const OcclusionOrder& order);

}  // namespace lfcam
