// libFuzzer target: the array file (`lfcam capture` reads it first) and the address patterns
// of `lfcam capture init`.
#include <cstdint>
#include <string>
#include <string_view>

#include "lfcam/capture/array_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto array = lfcam::ArrayFromJson(lfcam::ParseJsonBounded(text, "fuzz"), "fuzz");
    (void)lfcam::JsonToText(lfcam::ArrayToJson(array));
  } catch (const lfcam::Error&) {
  }
  try {
    (void)lfcam::NodesFromPattern(3, 4, std::string(text.substr(0, 128)));
  } catch (const lfcam::Error&) {
  }
  return 0;
}
