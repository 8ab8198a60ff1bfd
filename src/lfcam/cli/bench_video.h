#pragma once
// `lfcam bench video`: what `render --video` costs beyond its renders. Fig. 11 (a)'s refocus
// sweep (f 500, d_l 192, d_o 3400 -> 5200 mm), 60 frames of 1024^2, rendered with the frames
// only converted to sRGB, and rendered with them encoded to H.264 alongside (x264 veryfast,
// crf 18), the two alternated; the medians and the encoding's share are printed.
#include "lfcam/core/lightfield.h"
#include "lfcam/render/frame_renderer.h"

namespace lfcam::cli {

void BenchVideo(const LightField& lf, const FrameRenderer& renderer, Integrator integrator,
                Interpolation interpolation, int runs, bool quiet);

}  // namespace lfcam::cli
