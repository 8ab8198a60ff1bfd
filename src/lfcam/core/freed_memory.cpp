#include "lfcam/core/freed_memory.h"

#include <malloc.h>

#include <climits>

namespace lfcam {

void KeepFreedMemoryForReuse() {
  // Both, or neither: fixing one turns off glibc's moving thresholds for the other as well.
  ::mallopt(M_MMAP_THRESHOLD, 32 << 20);
  ::mallopt(M_TRIM_THRESHOLD, INT_MAX);
}

}  // namespace lfcam
