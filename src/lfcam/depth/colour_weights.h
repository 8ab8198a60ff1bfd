#pragma once
// The colour weight of the depth clean-up's kernels (depth/local_planes.cpp,
// depth/weighted_median.cpp), exp(n · scale) for a squared distance n between two 8-bit colours
// (over R, G and B: 0 … 3 · 255²), looked up rather than computed: the vector exponential was
// about half of the plane fit's time, a gather from this table about half as long
// (docs/benchmarks.md, "The clean-up's colour weights looked up"). Each entry is the float the
// kernels' own vector exponential (Highway's, on the instruction set the machine runs) gives for
// that n, so a map is the same to the last bit either way.
#include <vector>

namespace lfcam {

struct ColourWeights {
  // weight[n] for n = 0 … last; every larger distance weighs weight[last], which is 0 where the
  // exponential reaches 0 within the range (at every scale the clean-up uses).
  std::vector<float> weight;
  int last = 0;
};

// `scale` < 0 (−1 / (2 σ²), σ in 8-bit levels).
ColourWeights MakeColourWeights(float scale);

}  // namespace lfcam
