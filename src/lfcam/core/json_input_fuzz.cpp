// libFuzzer target: bounded JSON parsing and exact field reads, through the slab parser (the
// geometry every light field, calibration and import carries).
#include <cstdint>
#include <string_view>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/slab.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json j = lfcam::ParseJsonBounded(text, "fuzz");
    if (j.is_object()) {
      try {
        const lfcam::Slab slab = j.get<lfcam::Slab>();
        (void)slab.separation_mm();
      } catch (const lfcam::Error&) {
      }
      try {
        lfcam::JsonInteger(j, "i", -5, 1 << 20, "fuzz");
      } catch (const lfcam::Error&) {
      }
      try {
        lfcam::JsonUnsigned(j, "u", UINT64_MAX, "fuzz");
      } catch (const lfcam::Error&) {
      }
    }
    (void)lfcam::JsonToText(j);  // bounded nesting: no deep recursion here either
  } catch (const lfcam::Error&) {
  }
  return 0;
}
