#include "lfcam/core/limits.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/core/error.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

using testing::ErrorOf;
using testing::ScopedEnv;

TEST(Limits, MemoryBudgetComesFromTheMachineOrTheEnvironment) {
  const std::uint64_t machine = MemoryBudgetBytes();
  EXPECT_GT(machine, std::uint64_t(64) << 20);
  {
    const ScopedEnv limit("LFCAM_MEMORY_LIMIT", "2G");
    EXPECT_EQ(MemoryBudgetBytes(), std::uint64_t(2) << 30);
  }
  {
    const ScopedEnv limit("LFCAM_MEMORY_LIMIT", "1536k");
    EXPECT_EQ(MemoryBudgetBytes(), 1536u * 1024);
    EXPECT_NO_THROW(RequireMemory(1e6, "a small thing"));
    EXPECT_NE(ErrorOf([] {
                RequireMemory(1e9, "a big thing");
              }).find("a big thing needs 1.0 GB, more than the memory limit of 1.6 MB"),
              std::string::npos);
  }
  for (const char* bad : {"abc", "-5", "0", "12X", "", "1e999", "nan", "1e308G"}) {
    const ScopedEnv limit("LFCAM_MEMORY_LIMIT", bad);
    EXPECT_NE(ErrorOf([] { MemoryBudgetBytes(); }).find("LFCAM_MEMORY_LIMIT"), std::string::npos)
        << bad;
  }
  EXPECT_EQ(MemoryBudgetBytes(), machine);
}

TEST(Limits, RequireMemoryRefusesNonFiniteSizes) {
  EXPECT_THROW(RequireMemory(INFINITY, "x"), Error);
  EXPECT_THROW(RequireMemory(NAN, "x"), Error);
}

}  // namespace
}  // namespace lfcam
