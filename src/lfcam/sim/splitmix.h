#pragma once
// SplitMix64 (Steele, Lea and Flood 2014): a 64-bit state advanced by a fixed odd constant and
// mixed by a finaliser in which every input bit moves every output bit. The simulator's cheap,
// reproducible random numbers: sensor noise (camera_module.cpp) and where a pixel's rays fall
// within its strata (board_radiance.cpp).
#include <cstdint>

namespace lfcam {

inline constexpr std::uint64_t kSplitMixGamma = 0x9E3779B97F4A7C15ull;

inline std::uint64_t SplitMixFinalise(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// The next number of the sequence whose state is `state`, which it advances.
inline std::uint64_t SplitMixNext(std::uint64_t& state) {
  return SplitMixFinalise(state += kSplitMixGamma);
}

}  // namespace lfcam
