#include "lfcam/node/rpicam_video.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"

namespace lfcam {

std::vector<std::pair<std::size_t, std::size_t>> SplitMjpeg(std::string_view s,
                                                            const std::string& where) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  std::size_t at = 0;
  while (true) {
    const std::size_t soi = s.find("\xFF\xD8", at);
    if (soi == std::string_view::npos) break;
    const std::size_t eoi = s.find("\xFF\xD9", soi + 2);
    if (eoi == std::string_view::npos) break;  // the last frame, cut short
    out.emplace_back(soi, eoi + 2 - soi);
    at = eoi + 2;
  }
  if (out.empty()) throw Error(fmt::format("{}: no whole JPEG frame in the stream", where));
  return out;
}

std::vector<RpicamFrameTime> ParseRpicamMetadata(std::string_view text, const std::string& where) {
  // A stopped camera leaves the array unclosed, perhaps mid-object: cut back to the last whole
  // object and close it.
  std::string body(text);
  while (!body.empty() && std::isspace(static_cast<unsigned char>(body.back()))) body.pop_back();
  if (body.empty() || body.front() != '[')
    throw Error(fmt::format("{}: not a JSON array of per-frame metadata", where));
  if (body.back() != ']') {
    const std::size_t last = body.rfind('}');
    body = last == std::string::npos ? std::string("[]") : body.substr(0, last + 1) + "]";
  }
  nlohmann::json j;
  try {
    j = ParseJsonBounded(body, where);
  } catch (const Error&) {
    // The cut fell inside a nested object: drop one more object.
    const std::size_t end = body.rfind('}', body.size() - 3);
    const std::size_t start = end == std::string::npos ? std::string::npos : body.rfind('{', end);
    const std::size_t cut = start == std::string::npos ? std::string::npos : body.rfind('}', start);
    if (cut == std::string::npos) throw;
    j = ParseJsonBounded(body.substr(0, cut + 1) + "]", where);
  }
  if (!j.is_array()) throw Error(fmt::format("{}: not a JSON array of per-frame metadata", where));
  std::vector<RpicamFrameTime> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string w = fmt::format("{}: frame {}", where, i);
    if (!j[i].is_object()) throw Error(w + ": not an object");
    RpicamFrameTime t;
    t.sensor_ns = JsonInteger(j[i], "SensorTimestamp", 0, INT64_MAX, w);
    t.wall_clock_ns = JsonInteger(j[i], "FrameWallClock", 0, INT64_MAX, w);
    if (!out.empty() &&
        (t.sensor_ns <= out.back().sensor_ns || t.wall_clock_ns <= out.back().wall_clock_ns))
      throw Error(fmt::format("{}: its times are not after frame {}'s", w, i - 1));
    out.push_back(t);
  }
  return out;
}

std::vector<std::int64_t> SequenceFromSensorTimes(const std::vector<RpicamFrameTime>& times,
                                                  double fps) {
  std::vector<std::int64_t> out;
  for (const RpicamFrameTime& t : times) {
    auto k = std::int64_t(std::llround(double(t.sensor_ns - times.front().sensor_ns) * fps / 1e9));
    if (!out.empty() && k <= out.back()) k = out.back() + 1;  // jitter past half a period
    out.push_back(k);
  }
  return out;
}

}  // namespace lfcam
