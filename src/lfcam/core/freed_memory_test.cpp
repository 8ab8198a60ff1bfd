#include "lfcam/core/freed_memory.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstddef>
#include <cstring>
#include <memory>

namespace lfcam {
namespace {

long MinorFaults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// The page faults of writing a fresh block of `bytes`, then freeing it.
long FaultsOfAScratchBlock(std::size_t bytes) {
  const long before = MinorFaults();
  std::unique_ptr<char[]> block(new char[bytes]);
  std::memset(block.get(), 1, bytes);
  const volatile char last = block[bytes - 1];
  (void)last;
  block.reset();
  return MinorFaults() - before;
}

TEST(FreedMemory, AViewsScratchIsReusedNotFaultedInAgain) {
#ifdef LFCAM_TEST_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer's allocator ignores mallopt";
#endif
  KeepFreedMemoryForReuse();  // lfcam_tests' main has already; again changes nothing
  // A view's scratch, made and freed view after view, each block a little larger or smaller (as
  // views' windows are): once the heap holds the largest, the others fault no page in. Without
  // KeepFreedMemoryForReuse glibc unmaps or trims some of them, and the same loop (a program of
  // its own, one thread) faults 2 304 pages in again, and 61 444 for the four blocks of 60 MB
  // below; with it, none.
  constexpr std::size_t kMb = std::size_t(1) << 20;
  FaultsOfAScratchBlock(9 * kMb);
  long faults = 0;
  for (int view = 0; view < 8; ++view) faults += FaultsOfAScratchBlock((7 + view % 3) * kMb);
  EXPECT_LT(faults, 200) << "page faults over 8 views' scratch of 7-9 MB";
  // Beyond glibc's largest mmap threshold (32 MB) too: a full-size camera's float image.
  FaultsOfAScratchBlock(60 * kMb);
  faults = 0;
  for (int image = 0; image < 4; ++image) faults += FaultsOfAScratchBlock(60 * kMb);
  EXPECT_LT(faults, 200) << "page faults over 4 images' scratch of 60 MB";
}

}  // namespace
}  // namespace lfcam
