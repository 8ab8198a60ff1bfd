// libFuzzer target: reading a viewer script (`lfcam view --script FILE`).
#include <cstdint>
#include <string>

#include "lfcam/core/error.h"
#include "lfcam/viewer/viewer_script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    for (const lfcam::ScriptCommand& c : lfcam::ParseViewerScript(text, "fuzz"))
      (void)c.args.size();
  } catch (const lfcam::Error&) {
  }
  return 0;
}
