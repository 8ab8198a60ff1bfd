#include "lfcam/viewer/viewer_script.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <map>
#include <sstream>

#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"

namespace lfcam {
namespace {

constexpr std::uint64_t kMaxScriptBytes = 1 << 20;

struct Arity {
  int min, max;
  int numbers;  // how many leading arguments must be numbers
};

const std::map<std::string, Arity>& Commands() {
  static const std::map<std::string, Arity> commands = {
      {"window", {2, 2, 2}}, {"set", {2, 2, 0}},        {"click", {2, 2, 2}},
      {"drag", {4, 5, 4}},   {"key", {1, 1, 0}},        {"wait", {0, 0, 0}},
      {"frames", {1, 1, 1}}, {"screenshot", {1, 1, 0}}, {"capture", {1, 1, 0}},
      {"print", {0, 0, 0}},  {"quit", {0, 0, 0}},       {"camera", {2, 2, 2}},
      {"play", {0, 0, 0}},   {"pause", {0, 0, 0}},      {"seek", {1, 1, 1}},
      {"step", {1, 1, 1}},   {"loop", {1, 1, 0}},       {"wait-frame", {1, 1, 1}}};
  return commands;
}

// The keys a script can press (viewer/glfw_window.h: GlfwKeyFromName).
bool IsKeyName(const std::string& k) {
  if (k.size() == 1)
    return std::isalpha(static_cast<unsigned char>(k[0])) || k == "[" || k == "]" || k == "," ||
           k == ".";
  if (k == "Esc" || k == "Escape" || k == "Space" || k == "Home") return true;
  if (k.size() < 2 || k.size() > 3 || k[0] != 'F') return false;
  for (std::size_t i = 1; i < k.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(k[i]))) return false;
  const int n = std::stoi(k.substr(1));
  return n >= 1 && n <= 25;
}

bool IsNumber(const std::string& s) {
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

std::vector<ScriptCommand> ParseViewerScript(const std::string& text, const std::string& where) {
  std::vector<ScriptCommand> script;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    ScriptCommand c;
    c.line = number;
    if (!(words >> c.name) || c.name[0] == '#') continue;
    for (std::string w; words >> w;) c.args.push_back(w);
    const auto it = Commands().find(c.name);
    if (it == Commands().end())
      throw Error(fmt::format("{}:{}: unknown command '{}'", where, number, c.name));
    const Arity a = it->second;
    if (int(c.args.size()) < a.min || int(c.args.size()) > a.max)
      throw Error(fmt::format(
          "{}:{}: '{}' takes {} argument{}", where, number, c.name,
          a.min == a.max ? fmt::format("{}", a.min) : fmt::format("{} to {}", a.min, a.max),
          a.max == 1 ? "" : "s"));
    for (int k = 0; k < a.numbers; ++k)
      if (!IsNumber(c.args[std::size_t(k)]))
        throw Error(fmt::format("{}:{}: '{}': '{}' is not a number", where, number, c.name,
                                c.args[std::size_t(k)]));
    if (c.name == "key" && !IsKeyName(c.args[0]))
      throw Error(fmt::format(
          "{}:{}: unknown key '{}' (F1..F25, a letter, [, ], ',', '.', Space, Home, Esc)", where,
          number, c.args[0]));
    if (c.name == "loop" && c.args[0] != "on" && c.args[0] != "off")
      throw Error(fmt::format("{}:{}: loop is on or off", where, number));
    script.push_back(std::move(c));
  }
  return script;
}

std::vector<ScriptCommand> ReadViewerScript(const std::string& path) {
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path, kMaxScriptBytes, "viewer script");
  return ParseViewerScript(std::string(bytes.begin(), bytes.end()), path);
}

}  // namespace lfcam
