#pragma once
// Tests only: one simulated capture session shared by every test process of a build. ctest runs
// each suite in its own process (cmake/TestSuites.cmake), and several suites use the same
// session, so each would otherwise simulate it. The session lives in the temporary directory under
// a name made of `name` and the test binary's identity (size and time), so a rebuilt binary
// simulates afresh; sessions of other builds are removed. LFCAM_TEST_ARTIFACTS_KEY, when set,
// names the build instead: set for both passes, the sanitizer pass reads the sessions and
// calibrations the release pass made and checked (the simulator and the calibration still run
// under the sanitizers in the suites that test them). Processes that need it at once take
// turns (a lock file): the first simulates it, the others wait and use it. Anything else made from
// a session (its calibration) can be shared the same way.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

#include "lfcam/core/error.h"
#include "lfcam/sim/capture_simulation.h"

namespace lfcam::testing {

// The directory `name` made once per build by `make(dir)` and shared like the sessions: done when
// `dir / marker` exists. `make` must not itself ask for a shared artifact (the lock is held).
inline std::filesystem::path SharedTestArtifact(
    const std::string& name, const std::string& marker,
    const std::function<void(const std::filesystem::path&)>& make) {
  namespace fs = std::filesystem;
  std::string build;
  if (const char* key = std::getenv("LFCAM_TEST_ARTIFACTS_KEY"); key && *key) {
    build = "key-";
    for (const char* c = key; *c; ++c)
      build += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
  } else {
    struct stat self {};
    ::stat("/proc/self/exe", &self);
    build = std::to_string(self.st_size) + "-" + std::to_string(self.st_mtime);
  }
  const fs::path root =
      fs::temp_directory_path() / ("lfcam_test_captures_" + std::to_string(::getuid()));
  const fs::path dir = root / build / name;
  std::error_code ec;
  if (fs::exists(dir / marker, ec)) return dir;
  fs::create_directories(dir.parent_path(), ec);
  // One process at a time from here: the lock is released when the descriptor is closed.
  struct Lock {
    int fd;
    ~Lock() {
      if (fd >= 0) ::close(fd);
    }
  } lock{::open((root / (build + ".lock")).c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)};
  if (lock.fd >= 0) ::flock(lock.fd, LOCK_EX);
  if (fs::exists(dir / marker, ec)) return dir;                 // another process made it meanwhile
  for (const auto& entry : fs::directory_iterator(root, ec)) {  // other builds' sessions
    const std::string entry_name = entry.path().filename().string();
    if (entry_name != build && entry_name != build + ".lock") fs::remove_all(entry.path(), ec);
  }
  make(dir);
  return dir;
}

inline std::filesystem::path SharedTestCapture(const std::string& name,
                                               const CaptureSimulationOptions& options) {
  return SharedTestArtifact(name, "manifest.json", [&](const std::filesystem::path& dir) {
    SimulateCapture(MakePaperScene(), options, dir);
  });
}

}  // namespace lfcam::testing
