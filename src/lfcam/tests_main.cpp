// lfcam_tests' main: GoogleTest's, and exit status 77 when every test the filter selected was
// skipped (no data, no device), so that ctest, which runs one suite a process
// (cmake/TestSuites.cmake), reports such a suite as skipped rather than passed.
#include <gtest/gtest.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
  if (result == 0 && unit.test_to_run_count() > 0 && unit.successful_test_count() == 0 &&
      unit.skipped_test_count() == unit.test_to_run_count())
    return 77;
  return result;
}
