#pragma once
// The memory of the quadrilinear limit's filtered copy (render/quadrilinear_limit.h) kept from
// frame to frame on the CPU, its contents not: each frame filters all it reads, as it would in a
// fresh copy, but into pages an earlier frame already had the kernel map and clear (a fresh
// copy's first writes were about a quarter of the bench's limit frames: docs/benchmarks.md).
// `lfcam render --repeat`, the bench's tables, videos and paths, and the Python module render
// through one (FrameRenderer); the viewer keeps the filtered views themselves
// (render/prefilter_cache.h). It holds one copy's memory, the largest a frame needed, as long as
// it lives: at most the pages the frames wrote of it.
#include <mutex>

#include "lfcam/core/lightfield.h"

namespace lfcam {

class PrefilterMemory {
 public:
  // The memory held (none at first, or while another frame has it), taken out: frames rendered
  // at once on other threads get memory of their own.
  SampleBuffer Take();
  // Memory back after a frame: kept if it is larger than what is held.
  void Give(SampleBuffer memory);

 private:
  std::mutex mutex_;
  SampleBuffer held_;
};

}  // namespace lfcam
