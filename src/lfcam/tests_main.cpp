// lfcam_tests' main: GoogleTest's, and
// - exit status 77 when every test the filter selected was skipped (no data, no device), so that
//   ctest, which runs one suite a process (cmake/TestSuites.cmake), reports such a suite as
//   skipped rather than passed;
// - the scratch directories a test made (testing::MakeScratchDir) removed when it ends without
//   failing, and named when it fails, for a look at what it left;
// - freed memory kept for reuse, as in lfcam itself (core/freed_memory.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <system_error>

#include "lfcam/core/freed_memory.h"
#include "lfcam/core/test_support.h"

namespace {

class ScratchDirCleaner : public ::testing::EmptyTestEventListener {
  void OnTestEnd(const ::testing::TestInfo& test) override {
    auto& dirs = lfcam::testing::ScratchDirsOfTheRunningTest();
    for (const auto& dir : dirs) {
      if (test.result()->Failed()) {
        std::cout << "scratch directory kept: " << dir.string() << "\n";
      } else {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
      }
    }
    dirs.clear();
  }
};

}  // namespace

int main(int argc, char** argv) {
  lfcam::KeepFreedMemoryForReuse();  // as lfcam's own main does
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::UnitTest::GetInstance()->listeners().Append(new ScratchDirCleaner);
  const int result = RUN_ALL_TESTS();
  const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
  if (result == 0 && unit.test_to_run_count() > 0 && unit.successful_test_count() == 0 &&
      unit.skipped_test_count() == unit.test_to_run_count())
    return 77;
  return result;
}
