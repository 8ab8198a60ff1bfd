#pragma once
// The one exception type lfcam throws for bad input: its message names the file, camera or
// flag at fault and what is wrong, so the CLI can print it as it is.
#include <stdexcept>
#include <string>

namespace lfcam {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace lfcam
