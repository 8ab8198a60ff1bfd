#pragma once
// Accumulates renders of parts of the lens samples (VirtualCamera::WithLensSampleRange) into
// the frame the whole set gives: each part's average times its per-pixel count of rays that
// hit, summed, over the summed counts. The viewer refines a costly lens-samples frame this way,
// a part per display frame, and ends at the image `lfcam render` writes.
#include "lfcam/render/cpu_renderer.h"

namespace lfcam {

class LensSampleAccumulator {
 public:
  void Reset(int width, int height);
  void Add(const RenderResult& part);  // a render of the same camera over other lens samples
  RenderResult Frame() const;          // the average so far (0 where no ray has hit yet)
  int parts() const { return parts_; }

 private:
  cv::Mat sum_;     // CV_32FC3: Σ image × counts
  cv::Mat counts_;  // CV_32SC1
  long long rays_ = 0, rays_hit_ = 0;
  int parts_ = 0;
};

}  // namespace lfcam
