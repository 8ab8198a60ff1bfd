#pragma once
// Transparent huge pages for large buffers (the depth sweep's cost volumes, a light field's
// zeroed samples): a buffer of kHugePagesFrom bytes or more, aligned to kHugePageBytes and advised
// onto huge pages, faults 2 MB at a time instead of 4 KB.
#include <sys/mman.h>

#include <cstddef>

namespace lfcam {

inline constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;
inline constexpr std::size_t kHugePagesFrom = std::size_t(4) << 20;

// Advice only: where the kernel has no transparent huge pages the call fails and nothing
// changes.
inline void AdviseHugePages(void* start, std::size_t bytes) {
  ::madvise(start, bytes, MADV_HUGEPAGE);
}

}  // namespace lfcam
