#pragma once
// The Raspberry Pi camera through rpicam-apps (`rpicam-still`; `libcamera-still` on systems
// before Raspberry Pi OS Bookworm). The camera is kept running with the locked settings in
// rpicam-still's signal mode: each SIGUSR1 takes a still from the running sensor, so a capture
// costs at most one frame period (about 67 ms at 2592x1944 on the v1.3 module) rather than the
// hundreds of milliseconds of starting the camera (docs/hardware.md).
//
// The command is a template (--rpicam-command), split at spaces, with these placeholders:
//   {program} {width} {height} {exposure_us} {analogue_gain} {awb_red} {awb_blue} {denoise}
//   {jpeg_quality} {output}
// {output} is a file name pattern with a frame counter in the node's work folder. The camera
// must write one JPEG per SIGUSR1 there.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "lfcam/node/camera_backend.h"

namespace lfcam {

inline constexpr const char* kDefaultRpicamCommand =
    "{program} --nopreview --timeout 0 --signal --width {width} --height {height} --shutter "
    "{exposure_us} --gain {analogue_gain} --awbgains {awb_red},{awb_blue} --denoise {denoise} "
    "--quality {jpeg_quality} --output {output}";

// Video (`lfcam capture record`): rpicam-vid records Motion-JPEG for the recording's length and
// its per-frame metadata (node/rpicam_video.h). More placeholders: {fps} {timeout_ms}
// {metadata} (the metadata file), and {sync}, a word of its own that becomes `--sync server`,
// `--sync client` or nothing.
inline constexpr const char* kDefaultRpicamVideoCommand =
    "{program} --nopreview --timeout {timeout_ms} --framerate {fps} --width {width} --height "
    "{height} --shutter {exposure_us} --gain {analogue_gain} --awbgains {awb_red},{awb_blue} "
    "--denoise {denoise} --codec mjpeg --quality {jpeg_quality} {sync} --metadata {metadata} "
    "--metadata-format json --output {output}";

struct RpicamOptions {
  std::string command = kDefaultRpicamCommand;
  std::string program;                // empty: rpicam-still, else libcamera-still, on PATH
  std::filesystem::path work_folder;  // where the running camera writes its frames
  int warmup_ms = 1500;               // after starting the camera, before the first trigger
  std::string video_command = kDefaultRpicamVideoCommand;
  std::string video_program;  // empty: rpicam-vid, else libcamera-vid, on PATH
  // With libcamera's sync the clients follow the server only after it has counted its frames
  // (rpicam-apps' --sync-frames, 100 by default): the camera starts this much earlier.
  int sync_warmup_frames = 100;
};

// What a video command needs beyond the settings.
struct VideoCommandValues {
  double fps = 30;
  std::int64_t timeout_ms = 0;
  std::string metadata;
  std::string sync = "off";  // server, client or off
};

// The command line for `settings`, placeholders filled in. Throws lfcam::Error naming an
// unknown placeholder.
std::vector<std::string> ExpandCameraCommand(const std::string& command_template,
                                             const std::string& program,
                                             const CaptureSettings& settings,
                                             const std::string& output,
                                             const VideoCommandValues* video = nullptr);

std::unique_ptr<CameraBackend> MakeRpicamCamera(const RpicamOptions& options);

}  // namespace lfcam
