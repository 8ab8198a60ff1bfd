#pragma once
// Dark limbs (docs/depth.md, "Dark limbs kept"). A curved object's outermost samples, lit from
// the cameras' side, are shaded darker than both the object behind them and the background
// beside them. Their colour is then nearer the background's than the object's, and the
// weighted-median clean-up, which takes the sweep's fattening back, would move them onto the
// background: the object thinned by a sample all round. A
// background sample the sweep fattened onto an object has the background's colour, not a darker
// one; so a sample that a step would move farther is kept where its grey (the mean of R, G and B)
// lies at least `levels` below every sample of the farther side within `radius` samples and
// below the mean of its own side there.
#include <opencv2/core.hpp>

namespace lfcam {

struct DarkLimbOptions {
  double levels = 0;  // 0: no sample is a dark limb
  int radius = 3;     // the neighbourhood it is judged in, in samples
};

// Whether the sample at (x, y) of `label` (CV_32FC1, larger: farther; NaN: unknown), which a step
// would move to `farther`, is a dark limb of the object it is on. The farther side: the samples
// whose labels lie within `threshold` of `farther`; its own side: those within `threshold` of its
// own label. `guide_rgb8`: CV_8UC3 of the label's size.
bool IsDarkLimb(const cv::Mat& guide_rgb8, const cv::Mat& label, int x, int y, float farther,
                float threshold, const DarkLimbOptions& options);

}  // namespace lfcam
