#pragma once
// The exceptions lfcam throws for bad input: each message names the file, camera or flag at
// fault and what is wrong, so the CLI can print it as it is.
//
//   Error       something went wrong in the work (a corrupt file, a camera that cannot see):
//               the CLI exits with status 1;
//   UsageError  the command line itself is wrong (a flag's value, a missing argument): the
//               CLI exits with status 2, before any large file is read.
#include <stdexcept>
#include <string>

namespace lfcam {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

class UsageError : public Error {
 public:
  explicit UsageError(const std::string& message) : Error(message) {}
};

}  // namespace lfcam
