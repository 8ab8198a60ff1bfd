// libFuzzer target: reading a calibration.json back (what `lfcam build` trusts to place every
// camera), including the per-camera intrinsics, rotations and photometry.
#include <cstdint>
#include <string_view>

#include "lfcam/calib/calibration_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto c = lfcam::CalibrationFromJson(lfcam::ParseJsonBounded(text, "fuzz"), "fuzz");
    for (const auto& camera : c.cameras)
      if (camera.calibrated) (void)camera.intrinsics.Unproject(lfcam::Vec2(1, 1));
  } catch (const lfcam::Error&) {
  }
  return 0;
}
