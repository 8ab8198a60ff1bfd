#include "lfcam/cli/keyword_arguments.h"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "lfcam/core/error.h"

namespace lfcam::cli {
namespace {

std::string FlagOf(const std::string& keyword) {
  std::string flag = "--" + keyword;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

std::string Number(double value) { return fmt::format("{}", value); }

bool Whole(double value) { return std::isfinite(value) && value == std::floor(value); }

std::string Joined(const std::vector<double>& numbers) {
  std::vector<std::string> parts;
  for (double x : numbers) parts.push_back(Number(x));
  return fmt::format("{}", fmt::join(parts, ","));
}

// The flag's text for a value, or the reason it cannot be one.
std::string FlagText(const std::string& keyword, KeywordKind kind, const KeywordValue& value) {
  const auto wrong = [&](const char* expected) {
    return UsageError(fmt::format("{}: expected {}", keyword, expected));
  };
  if (const bool* b = std::get_if<bool>(&value)) {
    if (kind != KeywordKind::kSwitch) throw wrong("a value, not True or False");
    return *b ? "1" : "0";
  }
  if (kind == KeywordKind::kSwitch) throw wrong("True or False");
  if (const std::string* text = std::get_if<std::string>(&value)) {
    if (kind == KeywordKind::kNumber) throw wrong("a number, not a string");
    return *text;
  }
  if (const long long* n = std::get_if<long long>(&value)) {
    if (kind == KeywordKind::kNumber || kind == KeywordKind::kSize) return std::to_string(*n);
    throw wrong(kind == KeywordKind::kText ? "a string" : "a sequence of numbers");
  }
  if (const double* x = std::get_if<double>(&value)) {
    if (kind == KeywordKind::kNumber) return Number(*x);
    throw wrong(kind == KeywordKind::kText ? "a string" : "a sequence of numbers");
  }
  const auto& numbers = std::get<std::vector<double>>(value);
  switch (kind) {
    case KeywordKind::kVector3:
      if (numbers.size() != 3) throw wrong("3 numbers (x, y, z in mm)");
      return Joined(numbers);
    case KeywordKind::kPair:
      if (numbers.size() != 2) throw wrong("2 numbers (row, column)");
      return Joined(numbers);
    case KeywordKind::kQuad:
      if (numbers.size() != 4) throw wrong("4 numbers");
      return Joined(numbers);
    case KeywordKind::kSize:
      if (numbers.size() != 2 || !Whole(numbers[0]) || !Whole(numbers[1]) ||
          std::abs(numbers[0]) > 1e9 || std::abs(numbers[1]) > 1e9)
        throw wrong("2 whole numbers (width, height)");
      return fmt::format("{}x{}", static_cast<long long>(numbers[0]),
                         static_cast<long long>(numbers[1]));
    default:
      throw wrong(kind == KeywordKind::kText ? "a string" : "a number");
  }
}

}  // namespace

std::vector<std::string> KeywordTable::names() const {
  std::vector<std::string> out;
  for (const auto& entry : kinds) out.push_back(entry.first);
  return out;
}

const KeywordTable& RenderKeywordTable() {
  using K = KeywordKind;
  static const KeywordTable table{
      "render",
      {{"size", K::kSize},          {"eye", K::kVector3},         {"look_at", K::kVector3},
       {"up", K::kVector3},         {"focal_length", K::kNumber}, {"focus_distance", K::kNumber},
       {"aperture", K::kNumber},    {"lens_rate", K::kNumber},    {"no_breathing", K::kSwitch},
       {"camera", K::kText},        {"as_camera", K::kPair},      {"integrator", K::kText},
       {"interpolation", K::kText}, {"depth", K::kText},          {"antialias", K::kSwitch},
       {"depth_blend", K::kText},   {"threads", K::kNumber},      {"reference", K::kSwitch},
       {"backend", K::kText},       {"workgroup", K::kSize}}};
  return table;
}

const KeywordTable& ImportKeywordTable() {
  using K = KeywordKind;
  static const KeywordTable table{"import_views",
                                  {{"naming", K::kText},
                                   {"grid", K::kSize},
                                   {"rig", K::kText},
                                   {"st_distance", K::kNumber},
                                   {"pitch_mm", K::kNumber},
                                   {"st_res", K::kSize},
                                   {"st_domain", K::kQuad},
                                   {"st_windows", K::kText},
                                   {"focal_px", K::kNumber},
                                   {"focal_mm", K::kNumber},
                                   {"sensor_width_mm", K::kNumber},
                                   {"resampling", K::kText},
                                   {"chroma", K::kText},
                                   {"allow_missing", K::kSwitch},
                                   {"keep_dark_views", K::kSwitch},
                                   {"lenslet", K::kNumber},
                                   {"flip_rows", K::kSwitch},
                                   {"flip_cols", K::kSwitch},
                                   {"swap_axes", K::kSwitch},
                                   {"keep_axes", K::kSwitch}}};
  return table;
}

std::string InKeywords(const KeywordTable& table, std::string message) {
  std::vector<std::string> keywords = table.names();
  // Longest first, so that no flag's name is taken for another's beginning.
  std::sort(keywords.begin(), keywords.end(),
            [](const auto& a, const auto& b) { return a.size() > b.size(); });
  for (const std::string& keyword : keywords) {
    const std::string flag = FlagOf(keyword);
    for (std::size_t at = message.find(flag); at != std::string::npos;
         at = message.find(flag, at + keyword.size())) {
      const std::size_t end = at + flag.size();
      if (end < message.size() && (std::isalnum(static_cast<unsigned char>(message[end])) ||
                                   message[end] == '-' || message[end] == '_'))
        continue;
      message.replace(at, flag.size(), keyword);
    }
  }
  return message;
}

std::vector<std::string> FlagArguments(const KeywordTable& table,
                                       const std::vector<KeywordArgument>& arguments) {
  std::vector<std::string> args;
  std::set<std::string> seen;
  for (const KeywordArgument& argument : arguments) {
    const auto kind = table.kinds.find(argument.name);
    if (kind == table.kinds.end())
      throw UsageError(fmt::format("'{}' is not a keyword of {}; it takes: {}", argument.name,
                                   table.function, fmt::join(table.names(), ", ")));
    if (!seen.insert(argument.name).second)
      throw UsageError(fmt::format("{}: given twice", argument.name));
    const std::string text = FlagText(argument.name, kind->second, argument.value);
    if (kind->second == KeywordKind::kSwitch) {
      if (text == "1") args.push_back(FlagOf(argument.name));
      continue;
    }
    // One argument "--flag=text": a value that starts with '-' stays a value.
    args.push_back(FlagOf(argument.name) + "=" + text);
  }
  return args;
}

void ParseArguments(CLI::App& app, std::vector<std::string> args) {
  std::reverse(args.begin(), args.end());  // CLI11 takes its arguments last first
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
}

void ParseKeywords(CLI::App& app, const KeywordTable& table,
                   const std::vector<KeywordArgument>& arguments) {
  const std::vector<std::string> args = FlagArguments(table, arguments);
  try {
    ParseArguments(app, args);
  } catch (const UsageError& e) {
    throw UsageError(InKeywords(table, e.what()));
  }
}

}  // namespace lfcam::cli
