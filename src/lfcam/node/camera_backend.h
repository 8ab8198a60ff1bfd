#pragma once
// What a node's camera does, whatever drives it: a Raspberry Pi camera through rpicam-apps
// (rpicam_camera.h), a folder of images (replay_camera.h) or the simulated module
// (node/simulated_camera.h). The agent calls Prepare before the trigger time, Fire at it and
// Collect after, so that everything slow happens outside the instant that must line up.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "lfcam/node/capture_settings.h"
#include "lfcam/node/recording.h"

namespace lfcam {

struct ShotRequest {
  std::string id;    // the capture's id (file name on the node)
  std::string kind;  // "scene", "world" or "intrinsics"
  std::string shot;  // the shot's name in the session: "scene", "world", "shot_03"
};

// A video recording (node/recording.h): from the array's start time, for video.seconds at
// video.fps and video.width x video.height, with libcamera's software sync as video.sync says.
struct RecordRequest {
  std::string id, shot;
  std::int64_t start_unix_ns = 0;  // the array's first frame (the node's wall clock)
  VideoRecordInfo video;
};

// A frame as the camera delivers it.
struct CapturedFrame {
  std::int64_t sequence = 0, wall_clock_ns = 0, sensor_ns = 0;
  std::string jpeg;
};
using FrameSink = std::function<void(CapturedFrame&&)>;

struct CameraProbe {
  bool present = false;
  std::string model;   // "rpicam-still (ov5647)", "replay /srv/images", ...
  std::string detail;  // why not present, or anything worth knowing
};

class CameraBackend {
 public:
  virtual ~CameraBackend() = default;
  virtual std::string name() const = 0;
  virtual CameraProbe Probe() = 0;
  // Applies the settings the host locked (may restart a running camera). Throws lfcam::Error.
  virtual void Configure(const CaptureSettings& settings) = 0;
  // Before the trigger time: whatever can be done ahead (start the camera, load the image).
  virtual void Prepare(const ShotRequest& shot) = 0;
  // At the trigger time: as little as possible.
  virtual void Fire() = 0;
  // After Fire: the JPEG taken. Throws lfcam::Error when none comes within `timeout`.
  virtual std::string Collect(std::chrono::milliseconds timeout) = 0;
  // Records video, passing every frame to `sink` in order, until the recording's end or until
  // `stop` is set (then as soon as it can). Throws lfcam::Error when it cannot record; the
  // default: this camera records no video.
  virtual void Record(const RecordRequest& request, const FrameSink& sink,
                      const std::atomic<bool>& stop);
  // How long before the start time Record must be called for the camera to record from it.
  virtual std::chrono::milliseconds RecordLead(const VideoRecordInfo&) const {
    return std::chrono::milliseconds(0);
  }
  // A small JPEG for aiming and focusing, at most `max_width` pixels wide.
  virtual std::string Preview(int max_width) = 0;
};

}  // namespace lfcam
