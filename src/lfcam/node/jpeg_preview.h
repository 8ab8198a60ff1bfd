#pragma once
// A small copy of a JPEG for previews, without decoding it at full size: libjpeg's DCT scaling
// (1/2, 1/4 or 1/8) to the largest size at most `max_width` wide, then re-encoded.
#include <string>
#include <string_view>

namespace lfcam {

// Throws lfcam::Error naming `name` when `jpeg` is not a JPEG.
std::string ScaledJpeg(std::string_view jpeg, int max_width, int quality, const std::string& name);

}  // namespace lfcam
