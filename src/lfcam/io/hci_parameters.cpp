#include "lfcam/io/hci_parameters.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <initializer_list>

#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"

namespace lfcam {

namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

std::optional<double> HciParameters::focal_px() const {
  if (!focal_length_mm || !sensor_size_mm || !width_px || !height_px) return std::nullopt;
  return *focal_length_mm * std::max(*width_px, *height_px) / *sensor_size_mm;
}

double HciParameters::DepthOfDisparity(double d) const {
  if (!metric()) throw Error("parameters.cfg: no metric geometry to turn a disparity into depth");
  const double fb = *baseline_mm * *focal_px();
  return fb * *focus_distance_mm / (d * *focus_distance_mm + fb);
}

double HciParameters::DisparityOfDepth(double depth_mm) const {
  if (!metric()) throw Error("parameters.cfg: no metric geometry to turn a depth into disparity");
  return *baseline_mm * *focal_px() * (1.0 / depth_mm - 1.0 / *focus_distance_mm);
}

HciParameters ParseHciParameters(std::string_view text, const std::string& where) {
  if (text.size() > (std::size_t(1) << 20))
    throw Error(fmt::format("{}: {} bytes is too large for a parameters.cfg", where, text.size()));
  // A file saved by an editor that marks UTF-8 (a byte order mark) reads as one without.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  HciParameters p;
  p.source = where;
  std::map<std::string, int> line_of;
  std::string section;
  int line_number = 0;
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string_view line = Trim(text.substr(start, end - start));
    start = end + 1;
    ++line_number;
    if (line.empty() || line.front() == '#' || line.front() == ';') continue;
    if (line.front() == '[') {
      if (line.back() != ']' || line.size() < 3)
        throw Error(
            fmt::format("{}: line {}: a section header must read [name]", where, line_number));
      section = Lower(Trim(line.substr(1, line.size() - 2)));
      continue;
    }
    const auto eq = line.find_first_of("=:");
    if (eq == std::string_view::npos)
      throw Error(fmt::format("{}: line {}: expected 'key = value', found '{}'", where, line_number,
                              std::string(line.substr(0, 60))));
    const std::string key = Lower(Trim(line.substr(0, eq)));
    if (key.empty())
      throw Error(fmt::format("{}: line {}: a value without a key", where, line_number));
    const std::string full = section.empty() ? key : section + "." + key;
    if (p.values.count(full))
      throw Error(fmt::format("{}: line {}: {} is given twice (first on line {})", where,
                              line_number, full, line_of[full]));
    p.values[full] = std::string(Trim(line.substr(eq + 1)));
    line_of[full] = line_number;
  }

  auto number = [&](const std::string& key) -> std::optional<double> {
    const auto it = p.values.find(key);
    if (it == p.values.end()) return std::nullopt;
    const std::string& v = it->second;
    double value = 0;
    const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
    if (ec != std::errc() || ptr != v.data() + v.size() || !std::isfinite(value))
      throw Error(fmt::format("{}: line {}: {} = '{}' is not a number", where, line_of[key], key,
                              v.substr(0, 40)));
    return value;
  };
  auto positive = [&](const std::string& key, double max) -> std::optional<double> {
    const auto v = number(key);
    if (v && (!(*v > 0) || *v > max))
      throw Error(fmt::format("{}: line {}: {} = {} must be positive (at most {})", where,
                              line_of[key], key, *v, max));
    return v;
  };
  auto count = [&](const std::string& key, double max) -> std::optional<int> {
    const auto v = positive(key, max);
    if (!v) return std::nullopt;
    if (*v != std::floor(*v))
      throw Error(
          fmt::format("{}: line {}: {} = {} must be a whole number", where, line_of[key], key, *v));
    return int(*v);
  };
  // Keys that go together: all of `keys` or none.
  auto together = [&](std::initializer_list<const char*> keys, const char* what) {
    std::string given, missing;
    for (const char* key : keys) (p.values.count(key) ? given : missing) += std::string(" ") + key;
    if (!given.empty() && !missing.empty())
      throw Error(fmt::format("{}:{} given without{} ({})", where, given, missing, what));
  };
  p.focal_length_mm = positive("intrinsics.focal_length_mm", 1e6);
  p.width_px = count("intrinsics.image_resolution_x_px", kMaxImageSide);
  p.height_px = count("intrinsics.image_resolution_y_px", kMaxImageSide);
  p.sensor_size_mm = positive("intrinsics.sensor_size_mm", 1e6);
  p.cams_x = count("extrinsics.num_cams_x", kMaxViewsPerSide);
  p.cams_y = count("extrinsics.num_cams_y", kMaxViewsPerSide);
  p.baseline_mm = positive("extrinsics.baseline_mm", 1e9);
  if (const auto focus_m = positive("extrinsics.focus_distance_m", 1e9))
    p.focus_distance_mm = 1000.0 * *focus_m;
  p.disp_min = number("meta.disp_min");
  p.disp_max = number("meta.disp_max");
  together({"intrinsics.image_resolution_x_px", "intrinsics.image_resolution_y_px"},
           "the image's two sides go together");
  together({"extrinsics.num_cams_x", "extrinsics.num_cams_y"}, "the grid's two counts go together");
  if (p.focal_length_mm || p.sensor_size_mm)
    together({"intrinsics.focal_length_mm", "intrinsics.sensor_size_mm",
              "intrinsics.image_resolution_x_px", "intrinsics.image_resolution_y_px"},
             "a focal length in pixels needs the lens's focal length, the sensor's size and the "
             "image's");
  if (p.focus_distance_mm && !p.baseline_mm)
    throw Error(fmt::format(
        "{}: line {}: extrinsics.focus_distance_m given without extrinsics.baseline_mm (a "
        "distance in millimetres needs the cameras' spacing in millimetres)",
        where, line_of["extrinsics.focus_distance_m"]));
  return p;
}

}  // namespace lfcam
