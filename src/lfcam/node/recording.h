#pragma once
// A video recording as a node holds it (issue 24): the camera's frames as one Motion-JPEG stream
// (the JPEGs back to back, what `rpicam-vid --codec mjpeg` writes) and a frame index, one JSON
// line per frame appended once the frame's bytes are in the stream: its sequence number, where
// its bytes lie, and when it was exposed on the node's wall clock and on the sensor's clock
// (libcamera's FrameWallClock and SensorTimestamp). A node that dies mid-recording loses only
// the frame it was writing: the index never names bytes that are not there.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace lfcam {

struct VideoFrameEntry {
  std::int64_t sequence = 0;           // the camera's frame number (gaps: frames it dropped)
  std::uint64_t offset = 0, size = 0;  // the JPEG's bytes in the stream
  std::int64_t wall_clock_ns = 0;      // exposure start, the node's wall clock (Unix ns)
  std::int64_t sensor_ns = 0;          // the same instant on the sensor's clock (ns from boot)
};

nlohmann::json FrameEntryToJson(const VideoFrameEntry& entry);
VideoFrameEntry FrameEntryFromJson(const nlohmann::json& j, const std::string& where);

// The frame index's text: one line per frame. Parsing checks every line (fields, ranges), that
// sequence numbers and wall-clock times increase, and that the frames lie back to back in a
// stream of `stream_size` bytes; it stops at a last line cut short (a writer that died), and
// throws lfcam::Error naming the line for anything else.
std::vector<VideoFrameEntry> ParseFrameIndex(std::string_view text, std::uint64_t stream_size,
                                             const std::string& where);
std::string FrameIndexLine(const VideoFrameEntry& entry);

// What a node's recording is and how it ended.
struct VideoRecordInfo {
  double fps = 30;
  double seconds = 0;  // asked for
  int width = 0, height = 0;
  std::string sync = "off";     // "server", "client" (libcamera's software sync) or "off"
  std::int64_t stagger_ns = 0;  // this camera's frame starts are this much after the array's
  // "recording", "complete" (every frame asked for, less any the camera dropped), "truncated"
  // (the node stopped mid-recording: the frames before are kept) or "failed" (no frame).
  std::string status = "recording";
  std::int64_t frames = 0;
  std::string reason;  // why truncated or failed
};

nlohmann::json VideoInfoToJson(const VideoRecordInfo& info);
VideoRecordInfo VideoInfoFromJson(const nlohmann::json& j, const std::string& where);

}  // namespace lfcam
