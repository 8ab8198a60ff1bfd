#include "lfcam/core/freed_memory.h"

#include <malloc.h>

#include <climits>

namespace lfcam {

void KeepFreedMemoryForReuse() {
  // All three: fixing one threshold turns off glibc's moving thresholds for the other as well,
  // and blocks beyond the largest threshold (a full-size simulated camera's float image: 60 MB)
  // would still be mapped and unmapped each time were malloc allowed to map any.
  ::mallopt(M_MMAP_THRESHOLD, 32 << 20);
  ::mallopt(M_MMAP_MAX, 0);
  ::mallopt(M_TRIM_THRESHOLD, INT_MAX);
}

}  // namespace lfcam
