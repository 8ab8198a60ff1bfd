#include "lfcam/io/hci_parameters.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>

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

double HciParameters::focal_px() const {
  return focal_length_mm * std::max(width_px, height_px) / sensor_size_mm;
}

double HciParameters::DepthOfDisparity(double d) const {
  const double fb = baseline_mm * focal_px();
  return fb * focus_distance_mm / (d * focus_distance_mm + fb);
}

double HciParameters::DisparityOfDepth(double depth_mm) const {
  return baseline_mm * focal_px() * (1.0 / depth_mm - 1.0 / focus_distance_mm);
}

HciParameters ParseHciParameters(std::string_view text, const std::string& where) {
  if (text.size() > (std::size_t(1) << 20))
    throw Error(fmt::format("{}: {} bytes is too large for a parameters.cfg", where, text.size()));
  HciParameters p;
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

  auto number = [&](const std::string& key, bool required) -> std::optional<double> {
    const auto it = p.values.find(key);
    if (it == p.values.end()) {
      if (required) throw Error(fmt::format("{}: {} is missing", where, key));
      return std::nullopt;
    }
    const std::string& v = it->second;
    double value = 0;
    const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
    if (ec != std::errc() || ptr != v.data() + v.size() || !std::isfinite(value))
      throw Error(fmt::format("{}: line {}: {} = '{}' is not a number", where, line_of[key], key,
                              v.substr(0, 40)));
    return value;
  };
  auto positive = [&](const std::string& key, double max) {
    const double v = *number(key, true);
    if (!(v > 0) || v > max)
      throw Error(fmt::format("{}: line {}: {} = {} must be positive (at most {})", where,
                              line_of[key], key, v, max));
    return v;
  };
  auto count = [&](const std::string& key, double max) {
    const double v = positive(key, max);
    if (v != std::floor(v))
      throw Error(
          fmt::format("{}: line {}: {} = {} must be a whole number", where, line_of[key], key, v));
    return int(v);
  };
  p.focal_length_mm = positive("intrinsics.focal_length_mm", 1e6);
  p.width_px = count("intrinsics.image_resolution_x_px", kMaxImageSide);
  p.height_px = count("intrinsics.image_resolution_y_px", kMaxImageSide);
  p.sensor_size_mm = positive("intrinsics.sensor_size_mm", 1e6);
  p.cams_x = count("extrinsics.num_cams_x", kMaxViewsPerSide);
  p.cams_y = count("extrinsics.num_cams_y", kMaxViewsPerSide);
  p.baseline_mm = positive("extrinsics.baseline_mm", 1e9);
  p.focus_distance_mm = 1000.0 * positive("extrinsics.focus_distance_m", 1e9);
  p.disp_min = number("meta.disp_min", false);
  p.disp_max = number("meta.disp_max", false);
  return p;
}

}  // namespace lfcam
