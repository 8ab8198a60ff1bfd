// Fuzz target: a recording's per-frame metadata: the frame index a node keeps
// (node/recording.h, as a restarted node reads it), and what rpicam-vid leaves behind
// (node/rpicam_video.h: its JSON metadata, its Motion-JPEG stream).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lfcam/core/error.h"
#include "lfcam/node/recording.h"
#include "lfcam/node/rpicam_video.h"

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
  try {
    const auto times = lfcam::ParseRpicamMetadata(text, "fuzz");
    const auto sequence = lfcam::SequenceFromSensorTimes(times, 30);
    for (std::size_t i = 1; i < sequence.size(); ++i)
      if (sequence[i] <= sequence[i - 1]) __builtin_trap();
  } catch (const lfcam::Error&) {
  }
  try {
    for (const auto& [offset, n] : lfcam::SplitMjpeg(text, "fuzz"))
      if (offset + n > size) __builtin_trap();
  } catch (const lfcam::Error&) {
  }
  return 0;
}
