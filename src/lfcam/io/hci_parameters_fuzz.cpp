// libFuzzer target: the HCI benchmark's parameters.cfg (io/hci_parameters.h). Whatever it
// accepts has a positive focal length, baseline and focus distance where it gives them, a focus
// distance only beside a baseline, and, where it is metric, a finite depth for a disparity of
// zero (the focus distance itself).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "lfcam/core/error.h"
#include "lfcam/io/hci_parameters.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const lfcam::HciParameters p = lfcam::ParseHciParameters(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
    if (p.focal_px() && !(*p.focal_px() > 0)) std::abort();
    if (p.baseline_mm && !(*p.baseline_mm > 0)) std::abort();
    if (p.focus_distance_mm && !(*p.focus_distance_mm > 0 && p.baseline_mm)) std::abort();
    if (p.cams_x.has_value() != p.cams_y.has_value()) std::abort();
    if (p.metric() && !std::isfinite(p.DepthOfDisparity(0))) std::abort();
  } catch (const lfcam::Error&) {
  }
  return 0;
}
