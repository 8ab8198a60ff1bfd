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
// measure the gap). Where a camera's tent reaches past its view's window, the camera counts by
// the share of the tent inside, as the lens samples drop their rays one by one there
// (render/window_taper.h, QuadrilinearLimitTaper): it fades out rather than stepping. k is taken at
// the frame's central pixel: one filter per frame, exact when the plane of focus is parallel to the
// st-plane (a camera looking along the array's normal), close for a turned camera.
//
// On the CPU the filtered views are kept every m samples where the tent is wide
// (PrefilterStride), so that a frame's work follows its footprint on the views, not the light
// field's sampling; the GL renderer filters every sample.
#include <opencv2/core.hpp>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/virtual_camera.h"
#include "lfcam/render/window_taper.h"

namespace lfcam {

// The tent's half-widths in st samples along s and t (0: no filter).
struct StPrefilter {
  double h_s = 0, h_t = 0;
  double k = 0;  // the scale from uv offsets to st offsets
  // How many of the light field's samples apart the filtered copy keeps its samples along s and
  // t (PrefilteredCopy; 1: every sample). A copy kept m samples apart is read through the
  // bilinear read's tent of half-width m, so the taps carry less of the blur (PrefilterTaps).
  int stride_s = 1, stride_t = 1;
};
StPrefilter QuadrilinearLimitPrefilter(const LightField& lf, const VirtualCamera& camera);

// The stride (at least 1) at which the copy of a view filtered by the tent of half-width h
// keeps its samples: the largest m whose taps (a tent of half-width w, w^2 = h^2 + 1 - m^2) pass
// little near the copy's Nyquist frequency, w >= 2m (w >= 1.45 m for m of 2 and 3), so that
// its frames stay within about 50 dB of the whole copy's; the CPU's work then follows the
// frame's footprint on the views rather than the light field's sampling. `samples` (the view's
// extent along the axis): the copy keeps 16 or more.
int PrefilterStride(double h, int samples);

// The taps that filter a view's samples so that its bilinear reads are reads through the tent of
// half-width h (samples): the read's own tent_1 follows them, so they carry tent_h's part of
// tent_1 * tent_h, matched in its second moment (variance h^2 / 6): three taps [a, 1 - 2a, a]
// while that is at most 1/3, else the tent sampled at the integers with the width that gives
// it. Symmetric, normalised to 1; h = 0 gives {1}. For a copy kept every `stride` samples, read
// bilinearly between its own samples (a tent of half-width `stride` in the view's samples), the
// taps carry the rest of tent_1 * tent_h's variance: (h^2 + 1 - stride^2) / 6.
std::vector<float> PrefilterTaps(double h, int stride = 1);

// The samples of each view (row-major) that the cameras integrator reads for the frame, with
// the margin a bilinear read needs: camera c reads along its lines through the plane of focus,
// which meet the st-plane inside the quadrilateral of the frame's corners' lines (a plane maps
// to a plane by lines through a point). Empty rectangles for the views not in `views`; the
// whole view where a corner's line misses the st-plane.
std::vector<cv::Rect> ViewRegionsRead(const LightField& lf, const VirtualCamera& camera,
                                      const std::vector<bool>& views);

// The filtered copy's layout, all black (its pages mapped only as they are written): `lf`'s
// views kept every stride_s, stride_t samples, the same slab, poses and sample type. Copy
// sample k of a view stands on the view's own sample stride_s * (k + O) + (stride_s - 1) / 2 - o
// (rounded down), o its window's offset and O = floor(o / stride_s) the copy's
// (core/st_sampling.h); the copy's st domain starts where `lf`'s does (half a sample before it
// for an even stride, whose copy samples sit half a sample before their cells' centres) and ends
// up to a stride past it: each view's window covers the view's own, its outer samples repeating
// the edge. Strides 1: `lf`'s layout. With `memory` of at least PrefilteredCopyBytes, the copy
// lives in its first bytes instead, holding what they held (an earlier frame's copy: the
// frame's reads stay within the regions PrefilterViews writes, so nothing else is read).
LightField PrefilteredCopy(const LightField& lf, int stride_s, int stride_t,
                           const SampleBuffer& memory = {});
std::size_t PrefilteredCopyBytes(const LightField& lf, int stride_s, int stride_t);

// Writes into `out` (PrefilteredCopy(lf, prefilter.stride_s, prefilter.stride_t)) the views of
// `lf` filtered by the tent (in linear light, the views' edges replicated) inside
// `regions[row * cols + col]` (in `out`'s samples, as ViewRegionsRead(out, ...) gives them);
// the rest is left as it was (black in a fresh copy).
void PrefilterViews(const LightField& lf, const StPrefilter& prefilter,
                    const std::vector<cv::Rect>& regions, LightField* out);

// The fade at the views' edges (render/window_taper.h) for a render of `copy`, the views of
// `lf` filtered by `prefilter` (PrefilteredCopy(lf, prefilter.stride_s, prefilter.stride_t), or
// `lf`'s own layout for strides 1): the tent's half-widths in the copy's samples, and each of
// `lf`'s views' windows (the sampled domain where the views share it) in the copy's coordinates.
WindowTaper QuadrilinearLimitTaper(const LightField& lf, const LightField& copy,
                                   const StPrefilter& prefilter);

}  // namespace lfcam
