#pragma once
// Procedural textures that make focus and parallax obvious: fine checkers, stripes, text-like
// glyph rows, value noise, blotches with a grid (a globe), radial blades (a fan). Texture
// coordinates are millimetres on the surface, so detail sizes are physical.
#include "lfcam/core/geometry.h"

namespace lfcam {

enum class Pattern { kConstant, kChecker, kStripes, kNoise, kText, kBlotchGrid, kRadial };

struct Texture {
  Pattern pattern = Pattern::kConstant;
  Vec3 color_a = Vec3(0.5, 0.5, 0.5);  // linear RGB albedo
  Vec3 color_b = Vec3(0.1, 0.1, 0.1);
  double scale_mm = 10.0;  // checker square, stripe period, noise feature, glyph height, ...
  unsigned seed = 1;

  Vec3 Evaluate(const Vec2& uv_mm) const;
};

// Smooth value noise in [0, 1], fractal sum of 4 octaves; `p` in feature units.
double FractalNoise(const Vec2& p, unsigned seed);

}  // namespace lfcam
