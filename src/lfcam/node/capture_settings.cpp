#include "lfcam/node/capture_settings.h"

#include <fmt/format.h>

#include <algorithm>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"

namespace lfcam {

namespace {
constexpr const char* kDenoiseModes[] = {"off", "cdn_off", "cdn_fast", "cdn_hq"};
}

nlohmann::json SettingsToJson(const CaptureSettings& s) {
  return {{"width", s.width},
          {"height", s.height},
          {"exposure_us", s.exposure_us},
          {"analogue_gain", s.analogue_gain},
          {"awb_gains", {s.awb_red, s.awb_blue}},
          {"denoise", s.denoise},
          {"jpeg_quality", s.jpeg_quality}};
}

CaptureSettings SettingsFromJson(const nlohmann::json& j, const std::string& where,
                                 const CaptureSettings& base) {
  if (!j.is_object()) throw Error(fmt::format("{}: settings must be an object", where));
  CaptureSettings s = base;
  for (const auto& [key, value] : j.items()) {
    if (key == "width") {
      s.width = int(JsonInteger(j, "width", 16, 16384, where));
    } else if (key == "height") {
      s.height = int(JsonInteger(j, "height", 16, 16384, where));
    } else if (key == "exposure_us") {
      s.exposure_us = int(JsonInteger(j, "exposure_us", 1, 10'000'000, where));
    } else if (key == "analogue_gain") {
      s.analogue_gain = JsonNumber(j, "analogue_gain", where);
      if (s.analogue_gain < 1 || s.analogue_gain > 16)
        throw Error(fmt::format("{}: analogue_gain {} must be 1..16", where, s.analogue_gain));
    } else if (key == "awb_gains") {
      if (!value.is_array() || value.size() != 2)
        throw Error(fmt::format("{}: awb_gains must be [red, blue]", where));
      s.awb_red = JsonNumber(value[0], "", where + ": awb_gains[0]");
      s.awb_blue = JsonNumber(value[1], "", where + ": awb_gains[1]");
      for (double g : {s.awb_red, s.awb_blue})
        if (g <= 0 || g > 16)
          throw Error(fmt::format("{}: awb_gains {} must be in (0, 16]", where, g));
    } else if (key == "denoise") {
      s.denoise = JsonString(j, "denoise", where);
      if (std::find(std::begin(kDenoiseModes), std::end(kDenoiseModes), s.denoise) ==
          std::end(kDenoiseModes))
        throw Error(fmt::format("{}: denoise '{}' is not off, cdn_off, cdn_fast or cdn_hq", where,
                                s.denoise));
    } else if (key == "jpeg_quality") {
      s.jpeg_quality = int(JsonInteger(j, "jpeg_quality", 1, 100, where));
    } else {
      throw Error(fmt::format("{}: unknown setting '{}'", where, key));
    }
  }
  return s;
}

std::vector<std::string> SettingsDifferences(const CaptureSettings& node,
                                             const CaptureSettings& array) {
  std::vector<std::string> out;
  auto check = [&out](const char* name, const auto& a, const auto& b) {
    if (a != b) out.push_back(fmt::format("{} {} (array: {})", name, a, b));
  };
  check("width", node.width, array.width);
  check("height", node.height, array.height);
  check("exposure_us", node.exposure_us, array.exposure_us);
  check("analogue_gain", node.analogue_gain, array.analogue_gain);
  check("awb_red", node.awb_red, array.awb_red);
  check("awb_blue", node.awb_blue, array.awb_blue);
  check("denoise", node.denoise, array.denoise);
  check("jpeg_quality", node.jpeg_quality, array.jpeg_quality);
  return out;
}

}  // namespace lfcam
