// One plane of the plane sweep's cost volume from its sub-arrays' sums (sweep_costs.comp):
// each half-array's (and quarter-array's, where they count) sum and count over a box window (the
// edge repeated), its mean where enough of its views see the sample (a quarter-array's times
// quarter_weight), and the cheapest (where none has enough, the cheapest pair of opposite
// half-arrays'), as 16-bit cost units, into the
// volume at the plane's label (SweepViews::Sweep in depth/cost_volume.cpp does the same).
layout(local_size_x = 16, local_size_y = 8) in;

layout(binding = 0) uniform sampler2DArray sums;  // as sweep_costs.comp writes them
// Laid out label-fastest, as CostVolume keeps it: texel (plane, x), layer y.
layout(r16ui, binding = 1) writeonly uniform uimage2DArray volume;

uniform int plane;
uniform ivec2 size;
uniform int radius;
uniform float min_count;
uniform float pair_min_count;  // a pair of opposite half-arrays, where no half-array counts
uniform float unit;
uniform uint most;
uniform int sub_arrays;  // 8: the half-arrays; 16: the quarter-arrays too
uniform float quarter_weight;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  vec4 s0 = vec4(0.0), s1 = vec4(0.0), c0 = vec4(0.0), c1 = vec4(0.0);
  vec4 s2 = vec4(0.0), s3 = vec4(0.0), c2 = vec4(0.0), c3 = vec4(0.0);
  const bool quarters = sub_arrays > 8;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), size - 1);
      s0 += texelFetch(sums, ivec3(q, 0), 0);
      s1 += texelFetch(sums, ivec3(q, 1), 0);
      c0 += texelFetch(sums, ivec3(q, 2), 0);
      c1 += texelFetch(sums, ivec3(q, 3), 0);
      if (quarters) {
        s2 += texelFetch(sums, ivec3(q, 4), 0);
        s3 += texelFetch(sums, ivec3(q, 5), 0);
        c2 += texelFetch(sums, ivec3(q, 6), 0);
        c3 += texelFetch(sums, ivec3(q, 7), 0);
      }
    }
  bool found = false;
  float best = 0.0;
  for (int g = 0; g < 4; ++g) {
    if (c0[g] > min_count) {
      const float mean = s0[g] / c0[g];
      best = found ? min(best, mean) : mean;
      found = true;
    }
    if (c1[g] > min_count) {
      const float mean = s1[g] / c1[g];
      best = found ? min(best, mean) : mean;
      found = true;
    }
    if (quarters && c2[g] > min_count) {
      const float mean = quarter_weight * s2[g] / c2[g];
      best = found ? min(best, mean) : mean;
      found = true;
    }
    if (quarters && c3[g] > min_count) {
      const float mean = quarter_weight * s3[g] / c3[g];
      best = found ? min(best, mean) : mean;
      found = true;
    }
  }
  if (!found)
    for (int g = 0; g < 4; ++g) {
      const float c = c0[g] + c1[g];
      if (c > pair_min_count) {
        const float mean = (s0[g] + s1[g]) / c;
        best = found ? min(best, mean) : mean;
        found = true;
      }
    }
  const uint value = found ? uint(floor(best * unit + 0.5)) : most;
  imageStore(volume, ivec3(plane, p.x, p.y), uvec4(value, 0u, 0u, 0u));
}
