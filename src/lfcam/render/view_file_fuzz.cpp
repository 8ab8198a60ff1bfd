// libFuzzer target: reading a view file (what `lfcam render --camera` and `lfcam view --camera`
// trust: the viewer's screenshots write them, people edit them).
#include <cstdint>
#include <string_view>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/render/view_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const lfcam::ViewSettings view =
        lfcam::ViewFromJson(lfcam::ParseJsonBounded(text, "fuzz"), "fuzz");
    const lfcam::VirtualCamera camera(view.camera);
    (void)camera.pixel_direction(0, 0);
  } catch (const lfcam::Error&) {
  }
  return 0;
}
