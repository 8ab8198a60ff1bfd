#include "lfcam/node/recording.h"

#include <fmt/format.h>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/node/camera_backend.h"

namespace lfcam {

nlohmann::json FrameEntryToJson(const VideoFrameEntry& e) {
  return {{"sequence", e.sequence},
          {"offset", e.offset},
          {"size", e.size},
          {"wall_clock_ns", e.wall_clock_ns},
          {"sensor_ns", e.sensor_ns}};
}

VideoFrameEntry FrameEntryFromJson(const nlohmann::json& j, const std::string& where) {
  VideoFrameEntry e;
  e.sequence = JsonInteger(j, "sequence", 0, INT64_MAX, where);
  e.offset = JsonUnsigned(j, "offset", UINT64_MAX / 2, where);
  e.size = JsonUnsigned(j, "size", UINT64_MAX / 2, where);
  e.wall_clock_ns = JsonInteger(j, "wall_clock_ns", 0, INT64_MAX, where);
  e.sensor_ns = JsonInteger(j, "sensor_ns", 0, INT64_MAX, where);
  if (e.size < 4) throw Error(fmt::format("{}: a frame of {} bytes is no JPEG", where, e.size));
  return e;
}

std::string FrameIndexLine(const VideoFrameEntry& entry) {
  return FrameEntryToJson(entry).dump() + "\n";
}

std::vector<VideoFrameEntry> ParseFrameIndex(std::string_view text, std::uint64_t stream_size,
                                             const std::string& where) {
  std::vector<VideoFrameEntry> out;
  std::size_t start = 0;
  for (int line = 1; start < text.size(); ++line) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) break;  // the last line, cut short by a writer that died
    const std::string here = fmt::format("{}: line {}", where, line);
    const VideoFrameEntry e =
        FrameEntryFromJson(ParseJsonBounded(text.substr(start, end - start), here), here);
    start = end + 1;
    const std::uint64_t expected = out.empty() ? 0 : out.back().offset + out.back().size;
    if (e.offset != expected)
      throw Error(fmt::format("{}: frame {} starts at byte {}, the one before ends at {}", here,
                              e.sequence, e.offset, expected));
    if (!out.empty() && e.sequence <= out.back().sequence)
      throw Error(
          fmt::format("{}: frame {} follows frame {}", here, e.sequence, out.back().sequence));
    if (!out.empty() && e.wall_clock_ns <= out.back().wall_clock_ns)
      throw Error(fmt::format("{}: frame {}'s wall-clock time is not after frame {}'s", here,
                              e.sequence, out.back().sequence));
    if (e.offset + e.size > stream_size)
      break;  // named before its bytes were all written: the writer died there
    out.push_back(e);
  }
  return out;
}

nlohmann::json VideoInfoToJson(const VideoRecordInfo& v) {
  nlohmann::json j = {
      {"fps", v.fps},    {"seconds", v.seconds}, {"width", v.width},   {"height", v.height},
      {"sync", v.sync},  {"status", v.status},   {"frames", v.frames}, {"stagger_ns", v.stagger_ns},
      {"codec", "mjpeg"}};
  if (!v.reason.empty()) j["reason"] = v.reason;
  return j;
}

VideoRecordInfo VideoInfoFromJson(const nlohmann::json& j, const std::string& where) {
  VideoRecordInfo v;
  v.fps = JsonNumber(j, "fps", where);
  v.seconds = JsonNumber(j, "seconds", where);
  if (!(v.fps > 0 && v.fps <= 1000) || !(v.seconds > 0 && v.seconds <= 24 * 3600))
    throw Error(fmt::format("{}: fps must be in (0, 1000] and seconds in (0, 86400]", where));
  v.width = int(JsonInteger(j, "width", 16, 16384, where));
  v.height = int(JsonInteger(j, "height", 16, 16384, where));
  v.sync = JsonString(j, "sync", where);
  if (v.sync != "server" && v.sync != "client" && v.sync != "off")
    throw Error(fmt::format("{}: sync '{}' is not server, client or off", where, v.sync));
  v.stagger_ns = JsonInteger(j, "stagger_ns", 0, 1'000'000'000, where);
  v.status = JsonString(j, "status", where);
  if (v.status != "recording" && v.status != "complete" && v.status != "truncated" &&
      v.status != "failed")
    throw Error(fmt::format("{}: status '{}' is not recording, complete, truncated or failed",
                            where, v.status));
  v.frames = JsonInteger(j, "frames", 0, INT64_MAX, where);
  if (j.contains("reason")) v.reason = JsonString(j, "reason", where);
  return v;
}

void CameraBackend::Record(const RecordRequest&, const FrameSink&, const std::atomic<bool>&) {
  throw Error(fmt::format("the {} camera records no video", name()));
}

}  // namespace lfcam
