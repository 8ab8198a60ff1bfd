#pragma once
// Tests only: one simulated capture session shared by every test process of a build. ctest runs
// each test in its own process, so a fixture's SetUpTestSuite would otherwise simulate the same
// session once per test. The session lives in the temporary directory under a name made of
// `name` and the test binary's identity (size and time), so a rebuilt binary simulates afresh;
// sessions of other builds are removed. Processes racing to create it are safe: the simulator
// renames a complete session into place, and the loser uses the winner's.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "lfcam/core/error.h"
#include "lfcam/sim/capture_simulation.h"

namespace lfcam::testing {

inline std::filesystem::path SharedTestCapture(const std::string& name,
                                               const CaptureSimulationOptions& options) {
  namespace fs = std::filesystem;
  struct stat self {};
  ::stat("/proc/self/exe", &self);
  const std::string build = std::to_string(self.st_size) + "-" + std::to_string(self.st_mtime);
  const fs::path root =
      fs::temp_directory_path() / ("lfcam_test_captures_" + std::to_string(::getuid()));
  const fs::path dir = root / build / name;
  std::error_code ec;
  if (fs::exists(dir / "manifest.json", ec)) return dir;
  fs::create_directories(dir.parent_path(), ec);
  for (const auto& entry : fs::directory_iterator(root, ec))  // other builds' sessions
    if (entry.path().filename() != build) fs::remove_all(entry.path(), ec);
  try {
    SimulateCapture(MakePaperScene(), options, dir);
  } catch (const Error&) {
    if (!fs::exists(dir / "manifest.json", ec)) throw;  // not a lost race: a real failure
  }
  return dir;
}

}  // namespace lfcam::testing
