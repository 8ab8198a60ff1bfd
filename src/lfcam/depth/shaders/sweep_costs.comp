// One plane of the plane sweep's matching cost, on the GPU (depth/gl_cost_volume.h; the CPU's is
// SweepViews::Sweep in depth/cost_volume.cpp, and this computes the same): every view read
// shifted with Keys' cubic (the vertical taps first, the view's edge repeated; a view scaled as
// well, its camera off the reference's plane, at each sample's own fraction), compared with
// the reference (the mean absolute difference of the sRGB channels and the absolute difference
// of the grey gradients, each truncated, then weighted), and the cost added to the sums of the
// half-arrays (and, where they count, the quarter-arrays) the view belongs to.
layout(local_size_x = 16, local_size_y = 8) in;

layout(binding = 0) uniform isampler2DArray views_rgbx;  // channels 0 .. 3, a layer a view
layout(binding = 1) uniform isampler2DArray views_y;     // channel 4
layout(binding = 2) uniform sampler2D reference_rgbx;
layout(binding = 3) uniform sampler2D reference_y;

// ShiftedSweep::Read, with the view's sub-arrays.
struct Read {
  ivec4 origin;  // x0, y0, sub-arrays (bit g), scaled (1: read at scale.xy, scale.zw)
  vec4 wx;
  vec4 wy;
  ivec4 samples;  // x_lo, x_hi, y_lo, y_hi
  vec4 scale;     // a scaled view's ax, bx, ay, by: read at (ax x + bx, ay y + by)
};
layout(std430, binding = 0) readonly buffer Reads { Read reads[]; };

// Layers 0 and 1: the sums of half-arrays 0 .. 3 and 4 .. 7; layers 2 and 3: their counts;
// layers 4 to 7 the same for the quarter-arrays (sub-arrays 8 .. 15), where they count.
layout(rgba32f, binding = 0) writeonly uniform image2DArray sums;

uniform int plane;
uniform int view_count;
uniform ivec2 size;
uniform vec4 unit_rgbx;  // 1 / the packed channels' units
uniform float unit_y;
uniform vec4 terms;        // colour cap, gradient cap, colour weight, gradient weight
uniform int sub_arrays;    // 8: the half-arrays; 16: the quarter-arrays too
uniform float read_sigma;  // a scaled view's reads: 0 Keys' cubic, else a tapered Gaussian

// The weights of the samples at -1, 0, 1, 2 for a point at fraction f past sample 0: Keys' cubic
// (a = -0.5), or a Gaussian of read_sigma tapered to zero at 2 samples, normalised (as
// sweep::ReadWeights).
vec4 ReadWeights(float f) {
  const vec4 x = vec4(-1.0 - f, -f, 1.0 - f, 2.0 - f);
  if (read_sigma <= 0.0) {
    const float a = -0.5;
    const vec4 d = abs(x);
    const vec4 near = ((a + 2.0) * d - (a + 3.0)) * d * d + 1.0;
    const vec4 far = ((a * d - 5.0 * a) * d + 8.0 * a) * d - 4.0 * a;
    return mix(far, near, lessThanEqual(d, vec4(1.0)));
  }
  const vec4 taper = cos(3.14159265358979 * x / 4.0);
  const vec4 w = exp(-x * x / (2.0 * read_sigma * read_sigma)) * taper * taper;
  return w / (w.x + w.y + w.z + w.w);
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  const vec4 f = texelFetch(reference_rgbx, p, 0);
  const float f4 = texelFetch(reference_y, p, 0).r;
  float s[16], c[16];
  for (int g = 0; g < 16; ++g) {
    s[g] = 0.0;
    c[g] = 0.0;
  }
  for (int v = 0; v < view_count; ++v) {
    const Read r = reads[plane * view_count + v];
    if (p.x < r.samples.x || p.x > r.samples.y || p.y < r.samples.z || p.y > r.samples.w) continue;
    const ivec4 taps = ivec4(0, 1, 2, 3);
    // The first tap and the weights: the shift's, or a scaled view's own at this sample.
    ivec2 first = p + r.origin.xy - 1;
    vec4 wx = r.wx, wy = r.wy;
    if (r.origin.w != 0) {
      const vec2 t = r.scale.xz * vec2(p) + r.scale.yw;
      const vec2 whole = floor(t);
      first = ivec2(whole) - 1;
      wx = ReadWeights(t.x - whole.x);
      wy = ReadWeights(t.y - whole.y);
    }
    const ivec4 rows = clamp(ivec4(first.y) + taps, 0, size.y - 1);
    const ivec4 cols = clamp(ivec4(first.x) + taps, 0, size.x - 1);
    vec4 a = vec4(0.0);
    float a4 = 0.0;
    for (int i = 0; i < 4; ++i) {
      vec4 column = vec4(0.0);
      float column4 = 0.0;
      for (int j = 0; j < 4; ++j) {
        const ivec3 at = ivec3(cols[i], rows[j], v);
        column += wy[j] * vec4(texelFetch(views_rgbx, at, 0));
        column4 += wy[j] * float(texelFetch(views_y, at, 0).r);
      }
      a += wx[i] * column;
      a4 += wx[i] * column4;
    }
    a *= unit_rgbx;
    a4 *= unit_y;
    const float color = (abs(a.r - f.r) + abs(a.g - f.g) + abs(a.b - f.b)) * (1.0 / 3.0);
    const float gradient = abs(a.a - f.a) + abs(a4 - f4);
    const float cost = terms.z * min(color, terms.x) + terms.w * min(gradient, terms.y);
    const uint member = uint(r.origin.z);
    for (int g = 0; g < sub_arrays; ++g)
      if (((member >> uint(g)) & 1u) != 0u) {
        s[g] += cost;
        c[g] += 1.0;
      }
  }
  imageStore(sums, ivec3(p, 0), vec4(s[0], s[1], s[2], s[3]));
  imageStore(sums, ivec3(p, 1), vec4(s[4], s[5], s[6], s[7]));
  imageStore(sums, ivec3(p, 2), vec4(c[0], c[1], c[2], c[3]));
  imageStore(sums, ivec3(p, 3), vec4(c[4], c[5], c[6], c[7]));
  if (sub_arrays > 8) {
    imageStore(sums, ivec3(p, 4), vec4(s[8], s[9], s[10], s[11]));
    imageStore(sums, ivec3(p, 5), vec4(s[12], s[13], s[14], s[15]));
    imageStore(sums, ivec3(p, 6), vec4(c[8], c[9], c[10], c[11]));
    imageStore(sums, ivec3(p, 7), vec4(c[12], c[13], c[14], c[15]));
  }
}
