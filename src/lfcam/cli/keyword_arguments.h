#pragma once
// Commands' flags as keyword arguments: the Python module's lfcam.render(lf, focal_length=...)
// and lfcam.import_views(dir, rig=...). Each keyword is a flag's name without its dashes and with
// underscores (focus_distance for --focus-distance); its value becomes the flag's text, which
// the command's own flag code then parses and checks (ParseRenderKeywords, cli/render_flags.h;
// ParseImportKeywords, cli/import_flags.h), so the defaults, the limits and the messages are the
// command's, with the keywords' names in them.
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace CLI {
class App;
}

namespace lfcam::cli {

// A keyword's value as the caller gave it: True/False, a whole number, a number, a string, or a
// sequence of numbers (eye=(x, y, z), size=(w, h), as_camera=(r, c)).
using KeywordValue = std::variant<bool, long long, double, std::string, std::vector<double>>;

struct KeywordArgument {
  std::string name;
  KeywordValue value;
};

// What a keyword's value may be, by what its flag takes: a switch (True/False), a number, a
// string, 3 numbers (X,Y,Z), 2 numbers (R,C), a size (N or (W, H): WxH), 4 numbers (A,B,C,D).
enum class KeywordKind { kSwitch, kNumber, kText, kVector3, kPair, kSize, kQuad };

// One function's keywords: its name (for messages) and each keyword's kind.
struct KeywordTable {
  std::string function;
  std::map<std::string, KeywordKind> kinds;
  std::vector<std::string> names() const;
};

const KeywordTable& RenderKeywordTable();  // lfcam.render: `lfcam render`'s flags
const KeywordTable& ImportKeywordTable();  // lfcam.import_views: `lfcam import`'s

// The flags' arguments for the keywords ("--focal-length=500", "--no-breathing"), in the order
// given. Throws UsageError naming the keyword for one the table does not hold (listing those it
// does), one given twice, or a value of the wrong kind.
std::vector<std::string> FlagArguments(const KeywordTable& table,
                                       const std::vector<KeywordArgument>& arguments);

// A message of the flags' code with the keywords' names for the flags' ("--focal-length: ..."
// -> "focal_length: ...").
std::string InKeywords(const KeywordTable& table, std::string message);

// `args` (as typed, first to last) parsed by `app`, as a command line is; a parse error comes out
// as UsageError with CLI11's message.
void ParseArguments(CLI::App& app, std::vector<std::string> args);
// The keywords through `app`'s flags (FlagArguments, then ParseArguments); a bad keyword or value
// is a UsageError in the keywords' terms (InKeywords).
void ParseKeywords(CLI::App& app, const KeywordTable& table,
                   const std::vector<KeywordArgument>& arguments);

}  // namespace lfcam::cli
