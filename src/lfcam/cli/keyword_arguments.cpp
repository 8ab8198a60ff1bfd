#include "lfcam/cli/keyword_arguments.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "lfcam/core/error.h"

namespace lfcam::cli {
namespace {

// What a keyword's value may be, by what its flag takes.
enum class FlagKind { kSwitch, kNumber, kText, kVector3, kPair, kSize };

const std::map<std::string, FlagKind>& KeywordKinds() {
  static const std::map<std::string, FlagKind> kinds = {
      {"size", FlagKind::kSize},           {"eye", FlagKind::kVector3},
      {"look_at", FlagKind::kVector3},     {"up", FlagKind::kVector3},
      {"focal_length", FlagKind::kNumber}, {"focus_distance", FlagKind::kNumber},
      {"aperture", FlagKind::kNumber},     {"lens_rate", FlagKind::kNumber},
      {"no_breathing", FlagKind::kSwitch}, {"camera", FlagKind::kText},
      {"as_camera", FlagKind::kPair},      {"integrator", FlagKind::kText},
      {"interpolation", FlagKind::kText},  {"depth", FlagKind::kText},
      {"antialias", FlagKind::kSwitch},    {"threads", FlagKind::kNumber},
      {"reference", FlagKind::kSwitch},    {"backend", FlagKind::kText},
      {"workgroup", FlagKind::kSize}};
  return kinds;
}

std::string FlagOf(const std::string& keyword) {
  std::string flag = "--" + keyword;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

}  // namespace

std::string InKeywords(std::string message) {
  std::vector<std::string> keywords = RenderKeywords();
  // Longest first, so that no flag's name is taken for another's beginning.
  std::sort(keywords.begin(), keywords.end(),
            [](const auto& a, const auto& b) { return a.size() > b.size(); });
  for (const std::string& keyword : keywords) {
    const std::string flag = FlagOf(keyword);
    for (std::size_t at = message.find(flag); at != std::string::npos;
         at = message.find(flag, at + keyword.size())) {
      const std::size_t end = at + flag.size();
      if (end < message.size() &&
          (std::isalnum(static_cast<unsigned char>(message[end])) || message[end] == '-'))
        continue;
      message.replace(at, flag.size(), keyword);
    }
  }
  return message;
}

namespace {

std::string Number(double value) { return fmt::format("{}", value); }

bool Whole(double value) { return std::isfinite(value) && value == std::floor(value); }

// The flag's text for a value, or the reason it cannot be one.
std::string FlagText(const std::string& keyword, FlagKind kind, const KeywordValue& value) {
  const auto wrong = [&](const char* expected) {
    return UsageError(fmt::format("{}: expected {}", keyword, expected));
  };
  if (const bool* b = std::get_if<bool>(&value)) {
    if (kind != FlagKind::kSwitch) throw wrong("a value, not True or False");
    return *b ? "1" : "0";
  }
  if (kind == FlagKind::kSwitch) throw wrong("True or False");
  if (const std::string* text = std::get_if<std::string>(&value)) {
    if (kind == FlagKind::kNumber) throw wrong("a number, not a string");
    return *text;
  }
  if (const long long* n = std::get_if<long long>(&value)) {
    if (kind == FlagKind::kNumber) return std::to_string(*n);
    if (kind == FlagKind::kSize) return fmt::format("{}", *n);
    throw wrong(kind == FlagKind::kText ? "a string" : "a sequence of numbers");
  }
  if (const double* x = std::get_if<double>(&value)) {
    if (kind == FlagKind::kNumber) return Number(*x);
    throw wrong(kind == FlagKind::kText ? "a string" : "a sequence of numbers");
  }
  const auto& numbers = std::get<std::vector<double>>(value);
  switch (kind) {
    case FlagKind::kVector3:
      if (numbers.size() != 3) throw wrong("3 numbers (x, y, z in mm)");
      return fmt::format("{},{},{}", Number(numbers[0]), Number(numbers[1]), Number(numbers[2]));
    case FlagKind::kPair:
      if (numbers.size() != 2) throw wrong("2 numbers (row, column)");
      return fmt::format("{},{}", Number(numbers[0]), Number(numbers[1]));
    case FlagKind::kSize:
      if (numbers.size() != 2 || !Whole(numbers[0]) || !Whole(numbers[1]) ||
          std::abs(numbers[0]) > 1e9 || std::abs(numbers[1]) > 1e9)
        throw wrong("2 whole numbers (width, height)");
      return fmt::format("{}x{}", static_cast<long long>(numbers[0]),
                         static_cast<long long>(numbers[1]));
    default:
      throw wrong(kind == FlagKind::kText ? "a string" : "a number");
  }
}

}  // namespace

const std::vector<std::string>& RenderKeywords() {
  static const std::vector<std::string> keywords = [] {
    std::vector<std::string> names;
    for (const auto& entry : KeywordKinds()) names.push_back(entry.first);
    return names;
  }();
  return keywords;
}

std::vector<std::string> RenderFlagArguments(const std::vector<KeywordArgument>& arguments) {
  std::vector<std::string> args;
  std::set<std::string> seen;
  for (const KeywordArgument& argument : arguments) {
    const auto kind = KeywordKinds().find(argument.name);
    if (kind == KeywordKinds().end())
      throw UsageError(fmt::format("'{}' is not a keyword of render; it takes: {}", argument.name,
                                   fmt::join(RenderKeywords(), ", ")));
    if (!seen.insert(argument.name).second)
      throw UsageError(fmt::format("{}: given twice", argument.name));
    const std::string text = FlagText(argument.name, kind->second, argument.value);
    if (kind->second == FlagKind::kSwitch) {
      if (text == "1") args.push_back(FlagOf(argument.name));
      continue;
    }
    // One argument "--flag=text": a value that starts with '-' stays a value.
    args.push_back(FlagOf(argument.name) + "=" + text);
  }
  return args;
}

}  // namespace lfcam::cli
