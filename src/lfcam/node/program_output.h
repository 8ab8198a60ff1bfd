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

// What a program run to its end printed, and how it ended.
struct ProgramRun {
  bool started = false;  // false: not found on PATH, or not executable
  int exit_status = -1;  // its exit status; -1 when it did not exit normally (or did not start)
  std::string output;    // standard output, and standard error too where asked
};

// Runs `argv` (argv[0] looked up on PATH) to its end, reading everything it prints; standard
// error is discarded unless `with_stderr`, then it is read with standard output.
ProgramRun RunProgram(const std::vector<std::string>& argv, bool with_stderr = false);

// The first line `argv` prints on standard output, without its line end; nullopt when it cannot
// be started, prints nothing, or exits other than with status 0.
std::optional<std::string> FirstLineOfProgram(const std::vector<std::string>& argv);

}  // namespace lfcam
