#pragma once
// Sparse 3D points from a light field's depth maps, with their tracks: what COLMAP's
// points3D.txt holds (`lfcam export --format colmap --depth DIR`), and what Gaussian-splatting
// trainers start from. Every point is a confident depth sample of one view put in the world;
// its track is every view whose own depth map agrees that it sees the point there (the others
// are occluded or look past it).
#include <opencv2/core.hpp>
#include <vector>

#include "lfcam/core/geometry.h"
#include "lfcam/core/lightfield.h"
#include "lfcam/depth/depth_set.h"

namespace lfcam {

struct SparseObservation {
  double x = 0, y = 0;  // pixel in the exported view, COLMAP's convention (corners at integers)
  int point = 0;        // index into SparsePoints::points
};

struct SparsePoint {
  Vec3 position_mm = Vec3::Zero();  // lfcam's world frame
  cv::Vec3b rgb;                    // sRGB, from the view it came from
  // (view index row * cols + col, index into that view's observations), in view order.
  std::vector<std::pair<int, int>> track;
};

struct SparsePoints {
  std::vector<SparsePoint> points;
  std::vector<std::vector<SparseObservation>> observations;  // one list per view, row-major
};

struct SparsePointOptions {
  int stride = 0;               // every stride-th sample of a map (0: about 5 000 a view)
  double min_confidence = 0.5;  // of the sample a point comes from
  double agreement = 0.01;      // a view sees the point when its depth there is within this share
};

// Points from every map in `depth` (views nearest the centre first; a point already made from
// another view, within a stride's cell and 1% in depth, is not made again), each with its track
// over every view with a map. Views the light field records as filled from their neighbours
// (core/view_filling.h) give no points and are in no track: they are no photographs.
SparsePoints PointsFromDepth(const LightField& lf, const DepthSet& depth,
                             const SparsePointOptions& options = {});

}  // namespace lfcam
