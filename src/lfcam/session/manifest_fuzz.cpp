// libFuzzer target: a capture session's manifest (the first file calibrate and build read from
// a session someone else wrote) with its recordings' frames aligned, and the board SPEC strings of
// flags and manifests (a ChArUco board's layout too).
#include <cstdint>
#include <string>
#include <string_view>

#include "lfcam/calib/charuco.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/session/board.h"
#include "lfcam/session/frame_alignment.h"
#include "lfcam/session/session.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto m = lfcam::ManifestFromJson(lfcam::ParseJsonBounded(text, "fuzz"), "fuzz");
    (void)lfcam::JsonToText(lfcam::ManifestToJson(m));
    // A recording's frames grouped into light field frames, as capture report and build do.
    for (const lfcam::Shot& shot : m.shots)
      if (shot.kind == lfcam::ShotKind::kVideo) {
        try {
          const auto a = lfcam::AlignFrames(shot, m.rows, m.cols);
          (void)lfcam::SummarizeSpread(a);
        } catch (const lfcam::Error&) {
        }
      }
  } catch (const lfcam::Error&) {
  }
  try {
    const auto board = lfcam::ParseBoardSpec(std::string(text.substr(0, 64)));
    (void)board.corners();
    if (board.charuco()) (void)lfcam::MakeCharucoLayout(board);
  } catch (const lfcam::Error&) {
  }
  return 0;
}
