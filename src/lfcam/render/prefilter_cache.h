#pragma once
// The quadrilinear limit's filtered copy kept from frame to frame on the CPU, as the GL renderer
// keeps its prefiltered views (render/quadrilinear_limit.h): the tent depends on the light field
// and on where the frame is focused (k), not on the eye's place, the view's turn, the zoom or the
// aperture, so while the viewer moves through a light field at one focus, a frame filters only
// the samples no earlier frame filtered.
#include <mutex>
#include <opencv2/core.hpp>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/quadrilinear_limit.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

class PrefilterCache {
 public:
  // The copy of `lf` filtered by `prefilter` (its strides set) wherever `camera`'s frame reads
  // views `views` (ViewRegionsRead), filtering only what the kept copy lacks; a fresh copy when
  // the light field (its samples' buffer, its dimensions, its views' windows or its st domain)
  // or the filter changed. The reference stays valid until
  // the next call; one frame at a time.
  const LightField& Filtered(const LightField& lf, const StPrefilter& prefilter,
                             const VirtualCamera& camera, const std::vector<bool>& views);

  // The samples the last call filtered (0: the kept copy held them all), for the tests.
  long long last_filtered_samples() const { return last_filtered_samples_; }

 private:
  std::mutex mutex_;
  // The light field the copy is of: its samples (SampleBuffer::serial; 0: none) and layout.
  std::uint64_t serial_ = 0;
  LightFieldDims dims_{};
  std::vector<StOffset> offsets_;
  StDomain domain_;
  StPrefilter prefilter_;
  LightField copy_;
  SampleBuffer memory_;             // what copy_ lives in: kept when the filter changes
  std::vector<cv::Rect> filtered_;  // each view's filtered rectangle, in the copy's samples
  long long last_filtered_samples_ = 0;
};

}  // namespace lfcam
