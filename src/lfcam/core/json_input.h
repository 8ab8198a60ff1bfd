#pragma once
// Reading JSON that came from outside (file headers, manifests, calibration files, network
// requests): the size and nesting are bounded before nlohmann parses anything, and values are
// read exactly (an integer field holds an integer in range: no silent narrowing, wrapping or
// truncation of 10.7 to 10). Every error names `where` (a file, a field path) and throws
// lfcam::Error; no raw nlohmann message reaches a user.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "lfcam/core/geometry.h"
#include "lfcam/core/limits.h"

namespace lfcam {

// The deepest nesting of arrays and objects in `text` (strings, escapes included, are skipped).
int JsonNestingDepth(std::string_view text);

// Parses `text` after checking its size (<= kMaxJsonBytes) and nesting (<= max_depth).
nlohmann::json ParseJsonBounded(std::string_view text, const std::string& where,
                                int max_depth = kMaxJsonDepth);

// JSON text for output (files, --json, messages): bytes that are not UTF-8 (a file name, say) are
// replaced by U+FFFD instead of making nlohmann throw. indent < 0: one line.
std::string JsonToText(const nlohmann::json& j, int indent = -1);

// j[key] (or j itself when key is empty) as an exact integer in [min, max].
std::int64_t JsonInteger(const nlohmann::json& j, const char* key, std::int64_t min,
                         std::int64_t max, const std::string& where);
std::uint64_t JsonUnsigned(const nlohmann::json& j, const char* key, std::uint64_t max,
                           const std::string& where);
// j[key] as a finite number (integers accepted).
double JsonNumber(const nlohmann::json& j, const char* key, const std::string& where);
std::string JsonString(const nlohmann::json& j, const char* key, const std::string& where);
// j[key] as [x, y, z], each finite.
Vec3 JsonVec3(const nlohmann::json& j, const char* key, const std::string& where);
// j[key], which must be present (and an object when `object` is set).
const nlohmann::json& JsonField(const nlohmann::json& j, const char* key, const std::string& where);

// Checks a document's {"format": FORMAT, "version": N} header: an object of that format, of a
// version 1..newest. Returns the version; throws lfcam::Error naming `where` and `what` (for
// example "calibration") otherwise.
std::int64_t JsonFormatVersion(const nlohmann::json& j, const std::string& format,
                               std::int64_t newest, const std::string& what,
                               const std::string& where);

}  // namespace lfcam
