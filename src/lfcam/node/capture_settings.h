#pragma once
// The camera settings the host locks on every node of the array (docs/hardware.md): the same
// resolution, exposure time, analogue gain, white-balance gains, denoising and JPEG quality
// everywhere, so that the modules stop disagreeing on brightness and white balance (the paper's
// §7.1). A node refuses to capture when its settings differ from the array's.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lfcam {

struct CaptureSettings {
  int width = 2592, height = 1944;       // pixels, the sensor mode
  int exposure_us = 20000;               // shutter time
  double analogue_gain = 1.0;            // 1..16
  double awb_red = 1.6, awb_blue = 1.5;  // white-balance gains (AWB off)
  std::string denoise = "off";           // off | cdn_off | cdn_fast | cdn_hq (rpicam-apps' names)
  int jpeg_quality = 95;                 // 1..100

  bool operator==(const CaptureSettings&) const = default;
};

nlohmann::json SettingsToJson(const CaptureSettings& settings);
// Parses and range-checks settings; fields that are absent keep the values of `base`. Throws
// lfcam::Error naming `where` and the field.
CaptureSettings SettingsFromJson(const nlohmann::json& j, const std::string& where,
                                 const CaptureSettings& base = {});
// "exposure_us 10000 (array: 20000)", one entry per field that differs; empty when equal.
std::vector<std::string> SettingsDifferences(const CaptureSettings& node,
                                             const CaptureSettings& array);

}  // namespace lfcam
