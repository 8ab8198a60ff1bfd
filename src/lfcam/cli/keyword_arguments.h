#pragma once
// `render`'s flags as keyword arguments: the Python module's lfcam.render(lf, focal_length=...,
// aperture=...). Each keyword is a flag's name without its dashes and with underscores
// (focus_distance for --focus-distance); its value becomes the flag's text, which the command's
// own flag code then parses and checks (ParseRenderKeywords, cli/render_flags.h), so the
// defaults, the limits and the messages are `lfcam render`'s, with the keywords' names in them.
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace lfcam::cli {

// A keyword's value as the caller gave it: True/False, a whole number, a number, a string, or a
// sequence of numbers (eye=(x, y, z), size=(w, h), as_camera=(r, c)).
using KeywordValue = std::variant<bool, long long, double, std::string, std::vector<double>>;

struct KeywordArgument {
  std::string name;
  KeywordValue value;
};

// The keywords render() takes.
const std::vector<std::string>& RenderKeywords();

// The flags' arguments for the keywords ("--focal-length=500", "--no-breathing"), in the order
// given. Throws UsageError naming the keyword for one it does not know (listing those it does),
// one given twice, or a value of the wrong kind.
std::vector<std::string> RenderFlagArguments(const std::vector<KeywordArgument>& arguments);

// A message of the flags' code with the keywords' names for the flags' ("--focal-length: ..."
// -> "focal_length: ...").
std::string InKeywords(std::string message);

}  // namespace lfcam::cli
