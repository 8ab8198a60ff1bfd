#include "lfcam/core/json_input.h"

#include <fmt/format.h>

#include <cmath>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

std::string FieldName(const std::string& where, const char* key) {
  return key && *key ? fmt::format("{}: \"{}\"", where, key) : where;
}

const nlohmann::json& Value(const nlohmann::json& j, const char* key, const std::string& where) {
  return key && *key ? JsonField(j, key, where) : j;
}

std::string TypeOf(const nlohmann::json& v) {
  if (v.is_number_float()) return fmt::format("the number {}", JsonToText(v));
  return fmt::format("{} {}", v.type_name(), JsonToText(v).substr(0, 40));
}

}  // namespace

std::string JsonToText(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

int JsonNestingDepth(std::string_view text) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"')
      in_string = true;
    else if (c == '[' || c == '{')
      deepest = std::max(deepest, ++depth);
    else if ((c == ']' || c == '}') && depth > 0)
      --depth;
  }
  return deepest;
}

nlohmann::json ParseJsonBounded(std::string_view text, const std::string& where, int max_depth) {
  if (text.size() > kMaxJsonBytes)
    throw Error(fmt::format("{}: JSON of {} bytes is larger than the limit of {} bytes", where,
                            text.size(), kMaxJsonBytes));
  const int depth = JsonNestingDepth(text);
  if (depth > max_depth)
    throw Error(fmt::format("{}: JSON nests {} levels deep, more than the limit of {}", where,
                            depth, max_depth));
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(fmt::format("{}: malformed JSON at byte {}", where, e.byte));
  } catch (const nlohmann::json::exception&) {
    // out_of_range 406: a number beyond a double's range (found by json_input_fuzz).
    throw Error(fmt::format("{}: JSON holds a number out of range", where));
  }
}

const nlohmann::json& JsonField(const nlohmann::json& j, const char* key,
                                const std::string& where) {
  if (!j.is_object()) throw Error(fmt::format("{}: expected a JSON object", where));
  const auto it = j.find(key);
  if (it == j.end()) throw Error(fmt::format("{}: missing field \"{}\"", where, key));
  return *it;
}

std::int64_t JsonInteger(const nlohmann::json& j, const char* key, std::int64_t min,
                         std::int64_t max, const std::string& where) {
  const auto& v = Value(j, key, where);
  const std::string name = FieldName(where, key);
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (max >= 0 && u <= std::uint64_t(max) && std::int64_t(u) >= min) return std::int64_t(u);
    throw Error(fmt::format("{} is {}, outside {}..{}", name, u, min, max));
  }
  if (v.is_number_integer()) {
    const auto i = v.get<std::int64_t>();
    if (i >= min && i <= max) return i;
    throw Error(fmt::format("{} is {}, outside {}..{}", name, i, min, max));
  }
  throw Error(fmt::format("{} must be a whole number, not {}", name, TypeOf(v)));
}

std::uint64_t JsonUnsigned(const nlohmann::json& j, const char* key, std::uint64_t max,
                           const std::string& where) {
  const auto& v = Value(j, key, where);
  const std::string name = FieldName(where, key);
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u <= max) return u;
    throw Error(fmt::format("{} is {}, more than {}", name, u, max));
  }
  if (v.is_number_integer())
    throw Error(fmt::format("{} is {}, which is negative", name, v.get<std::int64_t>()));
  throw Error(fmt::format("{} must be a whole number, not {}", name, TypeOf(v)));
}

double JsonNumber(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto& v = Value(j, key, where);
  if (!v.is_number())
    throw Error(fmt::format("{} must be a number, not {}", FieldName(where, key), TypeOf(v)));
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw Error(fmt::format("{} must be finite", FieldName(where, key)));
  return d;
}

std::string JsonString(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto& v = Value(j, key, where);
  if (!v.is_string())
    throw Error(fmt::format("{} must be a string, not {}", FieldName(where, key), TypeOf(v)));
  return v.get<std::string>();
}

Vec3 JsonVec3(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto& v = Value(j, key, where);
  const std::string name = FieldName(where, key);
  if (!v.is_array() || v.size() != 3) throw Error(fmt::format("{} must be [x, y, z]", name));
  return {JsonNumber(v[0], "", name), JsonNumber(v[1], "", name), JsonNumber(v[2], "", name)};
}

std::int64_t JsonFormatVersion(const nlohmann::json& j, const std::string& format,
                               std::int64_t newest, const std::string& what,
                               const std::string& where) {
  if (!j.is_object() || JsonString(j, "format", where) != format)
    throw Error(fmt::format("{}: not an lfcam {} (format \"{}\")", where, what, format));
  const auto version = JsonInteger(j, "version", 1, 1000000, where);
  if (version > newest)
    throw Error(fmt::format("{}: {} version {} is newer than this lfcam reads ({})", where, what,
                            version, newest));
  return version;
}

}  // namespace lfcam
