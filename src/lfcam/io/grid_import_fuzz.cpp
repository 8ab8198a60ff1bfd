// libFuzzer target: what `lfcam import` reads before any image: the views' file names
// (Stanford and Blender camera-grid conventions) and lfcam-views.json.
#include <cstdint>
#include <string>
#include <string_view>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/io/grid_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)lfcam::ParseViewName(std::string(text.substr(0, 256)));
  try {
    (void)lfcam::GridFromDescription(lfcam::ParseJsonBounded(text, "fuzz"), "fuzz");
  } catch (const lfcam::Error&) {
  }
  return 0;
}
