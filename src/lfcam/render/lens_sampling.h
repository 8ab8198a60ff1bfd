#pragma once
// Sampling helpers for the thin lens (§6.2).
#include <vector>

#include "lfcam/core/geometry.h"

namespace lfcam {

// Shirley and Chiu's concentric map from the unit square [0,1)^2 to the unit disk: uniform
// density, low distortion.
Vec2 SampleUniformDiskConcentric(const Vec2& u);

// The paper's lens sample count n_ls = gamma * (d_l / 2)^2 / 210, rounded, at least 1.
int LensSampleCount(double lens_rate, double aperture_mm);

// The i-th point of an n-point Hammersley set in [0,1)^2: ((i + 0.5) / n, radical inverse of i
// shifted by 0.5 / n, modulo 1).
Vec2 Hammersley(int i, int n);

// n deterministic, well-spread points on the unit disk (Hammersley through the concentric
// map); every renderer uses the same set so CPU and GPU agree.
std::vector<Vec2> UnitDiskSamples(int n);

}  // namespace lfcam
