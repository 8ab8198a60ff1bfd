#pragma once
// Helpers shared by the tests (header-only; not part of the library).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam::testing {

// Whether the GL tests must run (LFCAM_REQUIRE_GL=1: scripts/test.sh installs Mesa), so that no
// GL context fails them instead of skipping them.
inline bool GlRequired() {
  const char* required = std::getenv("LFCAM_REQUIRE_GL");
  return required != nullptr && std::string(required) == "1";
}

// The scratch directories the running test has made (MakeScratchDir): removed when it ends
// without failing, kept and named when it fails (src/lfcam/tests_main.cpp).
inline std::vector<std::filesystem::path>& ScratchDirsOfTheRunningTest() {
  static std::vector<std::filesystem::path> dirs;
  return dirs;
}

// A fresh, empty directory for the running test: PREFIX_PID_TESTNAME in the temp directory (one
// per process and test: ctest runs suites in parallel processes). In a death test's child
// (GoogleTest's "threadsafe" style runs the test again in a process of its own), the parent
// test's directory as it is: what the child leaves there is what the parent then checks.
inline std::filesystem::path MakeScratchDir(const std::string& prefix) {
  const bool death_test_child = !GTEST_FLAG_GET(internal_run_death_test).empty();
  const auto dir = std::filesystem::temp_directory_path() /
                   (prefix + "_" + std::to_string(death_test_child ? ::getppid() : ::getpid()) +
                    "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  if (death_test_child) return dir;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ScratchDirsOfTheRunningTest().push_back(dir);
  return dir;
}

// The message of the lfcam::Error that f() throws, or "" when it throws none.
inline std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Sets an environment variable (LFCAM_MEMORY_LIMIT, say) for the life of the object.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) { ::setenv(name, value, 1); }
  ~ScopedEnv() { ::unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
};

// Runs `trials` inputs from make(trial) through consume(); counts those refused with
// lfcam::Error. Anything else (another exception, a crash, a sanitizer report) fails the test.
template <typename Make, typename Consume>
int CountRefused(int trials, Make make, Consume consume) {
  int refused = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const auto input = make(trial);
    try {
      consume(input);
    } catch (const Error&) {
      ++refused;
    }
  }
  return refused;
}

}  // namespace lfcam::testing
