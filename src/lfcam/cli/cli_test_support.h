#pragma once
// Tests only: runs the lfcam command (LFCAM_CLI_PATH, set by CMake) and captures what it prints.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace lfcam::testing {

struct CommandResult {
  int status;
  std::string output;  // stdout and stderr
};

inline CommandResult Lfcam(const std::string& args) {
  const std::string command = std::string(LFCAM_CLI_PATH) + " " + args + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  CommandResult run{-1, ""};
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) run.output += buffer.data();
  const int status = ::pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace lfcam::testing
