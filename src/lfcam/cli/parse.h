#pragma once
// Parsing helpers for flag values ("X,Y,Z", "WxH"); errors name the flag.
#include <string>
#include <utility>
#include <vector>

#include "lfcam/core/geometry.h"

namespace lfcam::cli {

std::vector<double> ParseNumbers(const std::string& flag, const std::string& text,
                                 std::size_t count, char separator = ',');
Vec3 ParseVec3(const std::string& flag, const std::string& text);
// "N" (square) or "WxH", each 1..65536.
std::pair<int, int> ParseSize(const std::string& flag, const std::string& text);

}  // namespace lfcam::cli
