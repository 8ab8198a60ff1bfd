#include "lfcam/render/prefilter_memory.h"

#include <utility>

namespace lfcam {

SampleBuffer PrefilterMemory::Take() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return std::exchange(held_, SampleBuffer());
}

void PrefilterMemory::Give(SampleBuffer memory) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (memory.size() > held_.size()) held_ = std::move(memory);
}

}  // namespace lfcam
