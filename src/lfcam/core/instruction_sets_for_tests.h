#pragma once
// The instruction sets a vectorised kernel's test runs it on: those Highway compiled in that this
// machine can run (on an AVX-512 machine: AVX3, AVX2, SSE4, SSSE3 and the emulated baseline),
// each chosen in turn with hwy::SetSupportedTargetsForTest, so that a kernel bug on any of them
// fails.
#include <hwy/targets.h>

#include <cstdint>
#include <vector>

namespace lfcam::testing {

inline std::vector<std::int64_t> InstructionSetsThisMachineRuns() {
  std::vector<std::int64_t> targets;
  for (std::int64_t t = 1; t != 0 && t <= HWY_TARGETS; t <<= 1)
    if ((HWY_TARGETS & t) && (hwy::SupportedTargets() & t)) targets.push_back(t);
  return targets;
}

}  // namespace lfcam::testing
