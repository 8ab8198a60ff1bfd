#pragma once
// Tools a node asks about its machine (chronyc, vcgencmd, rpicam-apps): found on the PATH and run
// directly, without a shell in between.
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace lfcam {

// The first of `names` that is an executable file in a folder of PATH (or of /usr/bin:/bin when
// PATH is unset), or empty.
std::string FindOnPath(std::initializer_list<const char*> names);

// Runs `argv` (argv[0] looked up on PATH), standard error discarded, and returns the first line it
// printed on standard output, without its line end; nullopt when it cannot be started, prints
// nothing, or exits other than with status 0.
std::optional<std::string> FirstLineOfProgram(const std::vector<std::string>& argv);

}  // namespace lfcam
