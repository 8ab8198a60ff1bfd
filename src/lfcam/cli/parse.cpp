#include "lfcam/cli/parse.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"

namespace lfcam::cli {

std::vector<double> ParseNumbers(const std::string& flag, const std::string& text,
                                 std::size_t count, char separator) {
  std::vector<double> out;
  std::size_t begin = 0;
  while (out.size() <= count) {  // one past `count` is enough to know it is too many
    const std::size_t end = std::min(text.find(separator, begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(value))
      throw UsageError(fmt::format("{}: '{}' is not a number (in '{}')", flag, item, text));
    out.push_back(value);
    if (end == text.size()) break;
    begin = end + 1;
  }
  if (out.size() != count)
    throw UsageError(fmt::format("{}: expected {} numbers separated by '{}', got '{}'", flag, count,
                                 separator, text));
  return out;
}

Vec3 ParseVec3(const std::string& flag, const std::string& text) {
  const auto v = ParseNumbers(flag, text, 3);
  return {v[0], v[1], v[2]};
}

std::pair<int, int> ParseSize(const std::string& flag, const std::string& text, int max_side) {
  const bool has_x = text.find('x') != std::string::npos;
  const auto v = has_x ? ParseNumbers(flag, text, 2, 'x') : ParseNumbers(flag, text, 1);
  const double w = v[0], h = has_x ? v[1] : v[0];
  if (w != std::floor(w) || h != std::floor(h) || w < 1 || h < 1 || w > max_side || h > max_side)
    throw UsageError(
        fmt::format("{}: '{}' must be N or WxH with whole numbers 1..{}", flag, text, max_side));
  return {int(w), int(h)};
}

StDomain ParseStDomain(const std::string& flag, const std::string& text) {
  const auto d = ParseNumbers(flag, text, 4);
  if (!(d[2] > d[0]) || !(d[3] > d[1]))
    throw UsageError(fmt::format("{}: '{}' needs S1 > S0 and T1 > T0", flag, text));
  for (const double x : d)
    if (std::abs(x) > kMaxStDomainBound)
      throw UsageError(
          fmt::format("{}: {} is outside -{}..{}", flag, x, kMaxStDomainBound, kMaxStDomainBound));
  return {d[0], d[1], d[2], d[3]};
}

bool ParseStWindows(const std::string& flag, const std::string& text) {
  if (text == "shared") return false;
  if (text == "views") return true;
  throw UsageError(fmt::format("{}: '{}' is not shared or views", flag, text));
}

void RequireNewOrEmptyFolder(const std::string& flag, const std::string& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) &&
      (!std::filesystem::is_directory(path, ec) || !std::filesystem::is_empty(path, ec)))
    throw UsageError(fmt::format("{} {}: exists and is not an empty folder", flag, path));
}

Compression ParseCompression(const std::string& flag, const std::string& text) {
  if (text == "none") return Compression::kNone;
  if (text == "zstd") return Compression::kZstd;
  throw UsageError(fmt::format("{}: '{}' is not none or zstd", flag, text));
}

}  // namespace lfcam::cli
