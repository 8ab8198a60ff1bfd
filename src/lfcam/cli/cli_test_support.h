#pragma once
// Tests only: runs the lfcam command (LFCAM_CLI_PATH, set by CMake) and captures what it prints.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace lfcam::testing {

struct CommandResult {
  int status;
  std::string output;  // stdout and stderr
};

inline CommandResult RunOnce(const std::string& command) {
  FILE* pipe = ::popen(command.c_str(), "r");
  CommandResult run{-1, ""};
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) run.output += buffer.data();
  const int status = ::pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

inline CommandResult Lfcam(const std::string& args) {
  // Appended, not concatenated: GCC 12 at -O3 warns falsely (-Warray-bounds) on the temporaries.
  std::string command = LFCAM_CLI_PATH;
  command.append(" ").append(args).append(" 2>&1");
  CommandResult run = RunOnce(command);
  // Under the asan preset, LeakSanitizer's own tracer now and then crashes at exit on a loaded
  // machine ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal error") after
  // the command has done its work: a fault of the tool, not of lfcam. Run such a command again,
  // once. A leak lfcam has is reported as "detected memory leaks" and is not retried.
  if (run.output.find("LeakSanitizer has encountered a fatal error") != std::string::npos)
    run = RunOnce(command);
  return run;
}

// Debian's Python, which the scripts in bench/ run under (scripts/install-deps.sh installs NumPy
// and OpenCV's module for it), where it imports `modules` (e.g. "numpy" or "cv2, numpy"); empty
// where it does not, for the test to skip saying so.
inline std::string PythonWith(const std::string& modules) {
  const std::string python =
      std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  return RunOnce(python + " -c 'import " + modules + "' 2>&1").status == 0 ? python : "";
}

}  // namespace lfcam::testing
