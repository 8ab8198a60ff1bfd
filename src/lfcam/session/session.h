#pragma once
// A capture session on disk (docs/capture-layout.md): what the capture controller writes, the
// simulator writes, and calibrate and build read.
//
//   DIR/manifest.json                       grid, sensor, boards, every shot's files
//   DIR/calib/intrinsics/shot_KK/cam_RR_CC.jpg   the intrinsics board, K = 00, 01, ...
//   DIR/calib/world/cam_RR_CC.jpg           the world board at the view window
//   DIR/scene/cam_RR_CC.jpg                 the scene
//   DIR/video/NAME/cam_RR_CC.mjpeg          a recording (its frames' times in the manifest)
//   DIR/ground_truth.json                   (simulated sessions only) what the simulator knows
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/session/board.h"

namespace lfcam {

inline constexpr const char* kManifestName = "manifest.json";
inline constexpr int kManifestVersion = 1;

// A recording (issue 24) is a shot too: each camera's "image" is its Motion-JPEG stream
// (DIR/video/NAME/cam_RR_CC.mjpeg), with its frames' times in the manifest.
enum class ShotKind { kIntrinsics, kWorld, kScene, kVideo };
std::string ToString(ShotKind kind);

// What the capture controller knows of a camera's image (docs/capture-layout.md): "ok", the file
// is in the session with its checksum verified; "captured", the node took it and holds it but it
// is not here yet (`lfcam capture fetch` gets it); "missing", the camera did not take it
// (`capture.reason` says why).
enum class ImageStatus { kOk, kCaptured, kMissing };
std::string ToString(ImageStatus status);

// A recorded frame of one camera: where its JPEG lies in the camera's stream, and when its
// exposure started on the node's wall clock (Unix ns; libcamera's FrameWallClock) and on the
// sensor's clock (SensorTimestamp).
struct FrameTime {
  std::int64_t sequence = 0;  // the camera's frame number: gaps are frames it dropped
  std::uint64_t offset = 0, size = 0;
  std::int64_t wall_clock_ns = 0, sensor_ns = 0;
  bool operator==(const FrameTime&) const = default;
};

struct ShotImage {
  ShotImage() = default;
  ShotImage(int r, int c, std::string f, ImageStatus s = ImageStatus::kOk,
            nlohmann::json record = nullptr)
      : row(r), col(c), file(std::move(f)), status(s), capture(std::move(record)) {}

  int row = 0, col = 0;
  std::string file;  // relative to the session directory, '/'-separated
  ImageStatus status = ImageStatus::kOk;
  // From the capture controller: node, requested and actual trigger time, settings, size,
  // sha256, reason. Null for sessions written otherwise.
  nlohmann::json capture;
  // A recording's camera: its frames, in order, once the node has said (empty before).
  std::vector<FrameTime> frames;
};

// How a recording was made: what every node was asked for.
struct VideoShot {
  double fps = 30, seconds = 0;
  int width = 0, height = 0;       // the video's sensor mode
  std::string sync = "off";        // "on": libcamera's software sync, one node the server
  std::int64_t start_unix_ns = 0;  // the first frame's time (the host's clock)
  int groups = 1;                  // staggered: group g's frames start g / (groups * fps) later
};

struct Shot {
  Shot() = default;
  Shot(ShotKind k, std::string n, std::vector<ShotImage> i = {}, std::vector<ShotImage> p = {})
      : kind(k), name(std::move(n)), images(std::move(i)), pending(std::move(p)) {}

  ShotKind kind = ShotKind::kScene;
  std::string name;                // "shot_00", "world", "scene"
  std::vector<ShotImage> images;   // the images in the session (status ok)
  std::vector<ShotImage> pending;  // the cameras whose image is not (captured or missing)
  std::optional<VideoShot> video;  // kVideo's
};

struct CaptureManifest {
  int rows = 10, cols = 10;
  double pitch_mm = 28.0;
  int sensor_width = 0, sensor_height = 0;
  std::string sensor_model;
  std::optional<BoardSpec> intrinsics_board, world_board;
  std::vector<Shot> shots;
  nlohmann::json source = nlohmann::json::object();  // who made it, when, with what settings

  std::vector<const Shot*> shots_of(ShotKind kind) const;
};

// "cam_RR_CC.jpg" (at least two digits each).
std::string CameraFileName(int row, int col);
// "camera (R, C)" for messages.
std::string CameraLabel(int row, int col);

nlohmann::json ManifestToJson(const CaptureManifest& manifest);
// A camera's frames as the manifest lists them: [sequence, offset, size, wall_clock_ns,
// sensor_ns] each, in order, back to back in the stream from byte 0, sequence and wall-clock time
// increasing. Throws lfcam::Error naming `where` and the frame.
std::vector<FrameTime> FramesFromJson(const nlohmann::json& j, const std::string& where);
// Parses a manifest; `where` names it in errors. File names must be relative and stay inside
// the session (no "..", no absolute paths); each camera appears at most once per shot; row and
// col are inside the grid.
CaptureManifest ManifestFromJson(const nlohmann::json& j, const std::string& where);
// Reads DIR/manifest.json (bounded, regular file). Throws lfcam::Error naming the file. When the
// session has no manifest.json, the manifest is read from the layout instead (ScanSessionLayout).
CaptureManifest ReadManifest(const std::filesystem::path& session_dir);

// A manifest from the folder and file names alone, for a session written by another tool:
// calib/intrinsics/*/cam_RR_CC.{jpg,jpeg,png} (one shot per folder, in name order),
// calib/world/cam_RR_CC.*, scene/cam_RR_CC.*. The grid is the largest row and column found, the
// sensor size the first image's, the pitch 28 mm; no boards (give them as flags). Throws
// lfcam::Error when there is no such layout.
CaptureManifest ScanSessionLayout(const std::filesystem::path& session_dir);

}  // namespace lfcam
