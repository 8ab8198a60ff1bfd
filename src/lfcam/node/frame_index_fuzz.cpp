// Fuzz target: a recording's frame index (node/recording.h), as a restarted node reads it.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lfcam/core/error.h"
#include "lfcam/node/recording.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto frames = lfcam::ParseFrameIndex(text, 1u << 20, "fuzz");
    std::uint64_t end = 0;
    for (const auto& f : frames) {
      if (f.offset != end || f.offset + f.size > (1u << 20)) __builtin_trap();
      end = f.offset + f.size;
    }
  } catch (const lfcam::Error&) {
  }
  return 0;
}
