#pragma once
// The limit of the paper's own estimator (lens samples with the quadrilinear lookup) as the lens
// sampling rate grows: `--integrator cameras --interpolation quadrilinear`
// (../shared/DESIGN.md, "The aperture integral"). Camera c's line through the point in focus
// p_o and a uv point C_c + delta meets the st-plane at S_c + k delta, k = -h_o / (h_uv - h_o)
// (heights above the st-plane of p_o and of the array). So over its bilinear hat, camera c is
// read at S_c through the hat scaled by k: its view prefiltered by a tent of half-width |k| pitch
// on the st-plane (the taps carry the tent's spread; the read's bilinear tent adds the rest),
// weighted as the cameras integrator weights it. The limit is therefore the
// cameras integrator (the focal-plane reads, render/camera_integrator.h) over views filtered by
// that tent: the paper's smooth out-of-focus blur without its lens-sample noise.
//
// Exact where the aperture's footprint covers a camera's whole hat; for the cameras at the
// footprint's rim, whose hats it cuts, the whole tent stands in for the cut one (the tests
// measure the gap). k is taken at the frame's central pixel: one filter per frame, exact when
// the plane of focus is parallel to the st-plane (a camera looking along the array's normal),
// close for a turned camera.
#include <opencv2/core.hpp>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

// The tent's half-widths in st samples along s and t (0: no filter).
struct StPrefilter {
  double h_s = 0, h_t = 0;
  double k = 0;  // the scale from uv offsets to st offsets
};
StPrefilter QuadrilinearLimitPrefilter(const LightField& lf, const VirtualCamera& camera);

// The taps that filter a view's samples so that its bilinear reads are reads through the tent of
// half-width h (samples): the read's own tent_1 follows them, so they carry tent_h's part of
// tent_1 * tent_h, matched in its second moment (variance h^2 / 6): three taps [a, 1 - 2a, a]
// while that is at most 1/3, else the tent sampled at the integers with the width that gives
// it. Symmetric, normalised to 1; h = 0 gives {1}.
std::vector<float> PrefilterTaps(double h);

// The samples of each view (row-major) that the cameras integrator reads for the frame, with
// the margin a bilinear read needs: camera c reads along its lines through the plane of focus,
// which meet the st-plane inside the quadrilateral of the frame's corners' lines (a plane maps
// to a plane by lines through a point). Empty rectangles for the views not in `views`; the
// whole view where a corner's line misses the st-plane.
std::vector<cv::Rect> ViewRegionsRead(const LightField& lf, const VirtualCamera& camera,
                                      const std::vector<bool>& views);

// A light field whose views are `lf`'s filtered by the tent (in linear light, the views' edges
// replicated) inside `regions[row * cols + col]`; the rest is left black. Same slab, measured
// poses and sample type.
LightField PrefilterViews(const LightField& lf, const StPrefilter& prefilter,
                          const std::vector<cv::Rect>& regions);

}  // namespace lfcam
