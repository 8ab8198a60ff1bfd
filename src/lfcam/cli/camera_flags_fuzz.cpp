// libFuzzer target: the flag parsers (numbers, vectors, sizes) and the virtual camera flags,
// validated and turned into a camera, with values a user could type; and the flags as
// `render --video` parses them (ranges A:B swept), every frame's camera made.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "lfcam/cli/camera_flags.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"
#include "lfcam/render/camera_path.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  lfcam::cli::CameraFlags flags;
  flags.size = in.ConsumeRandomLengthString(24);
  if (in.ConsumeBool()) flags.eye = in.ConsumeRandomLengthString(48);
  if (in.ConsumeBool()) flags.look_at = in.ConsumeRandomLengthString(48);
  if (in.ConsumeBool()) flags.up = in.ConsumeRandomLengthString(48);
  flags.focal_length_mm = in.ConsumeFloatingPoint<double>();
  flags.focus_distance_mm = in.ConsumeFloatingPoint<double>();
  flags.aperture_mm = in.ConsumeFloatingPoint<double>();
  flags.lens_rate = in.ConsumeFloatingPoint<double>();
  flags.no_breathing = in.ConsumeBool();
  try {
    flags.Validate();
    const lfcam::VirtualCamera camera = flags.MakeCamera(lfcam::ArrayPlane{});
    if (camera.lens_samples().empty()) std::abort();
    (void)camera.pixel_direction(camera.width() - 1, camera.height() - 1);
  } catch (const lfcam::Error&) {
  }
  {
    // The sweepable flags through CLI11, as `render --video` takes them.
    std::vector<std::string> args;
    for (const char* flag :
         {"--focus-distance", "--aperture", "--focal-length", "--eye", "--look-at"})
      if (in.ConsumeBool()) {
        args.push_back(flag);
        args.push_back(in.ConsumeRandomLengthString(40));
      }
    try {
      const auto parsed = lfcam::cli::ParseCameraFlags(args, /*rig_cameras=*/true, /*sweeps=*/true);
      const lfcam::cli::CameraFlags& swept = parsed->flags;
      swept.Validate();
      const lfcam::CameraPath path =
          lfcam::CameraPath::Sweep(swept.MakeCamera(lfcam::ArrayPlane{}).params(), swept.sweep());
      for (int k = 0; k < 5; ++k) (void)lfcam::VirtualCamera(path.AtFrame(k, 5));
    } catch (const lfcam::Error&) {
    }
  }
  const std::string text = in.ConsumeRemainingBytesAsString();
  for (const char separator : {',', 'x'}) try {
      lfcam::cli::ParseNumbers("--fuzz", text, 4, separator);
    } catch (const lfcam::Error&) {
    }
  try {
    lfcam::cli::ParseSize("--fuzz", text, 65536);
  } catch (const lfcam::Error&) {
  }
  // LFCAM_MEMORY_LIMIT's parser: never throws, a size is positive and finite.
  if (const auto bytes = lfcam::ParseByteSize(text); bytes && !(*bytes > 0 && *bytes < INFINITY))
    std::abort();
  return 0;
}
