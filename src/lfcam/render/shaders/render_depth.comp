// The depth lookup on the GPU (`--interpolation depth --backend gl`): the GL twin of
// render/depth_aware_sampler.cpp and the CPU renderer's lens-sample loop over it
// (render/cpu_renderer.cpp, RenderPixel and RenderPixelDepth), one invocation a pixel. Each ray
// is read from the (up to four) cameras around where it crosses the uv-plane; each camera
// marches along the ray through its depth map to the surface it sees, the hit most of the
// cameras' weight agrees with wins, and the cameras that agree are read where that point
// projects into them (and, with agreeing_blend, the agreeing cameras within two steps:
// BlendAgreeing). A ray no camera finds a hit for falls back to the paper's lookup.
//
// World positions arrive relative to the array's corner p_ca (computed in double on the C++
// side), so that float keeps a thousandth of a millimetre. The C++ side prepends
// "#version 430 core" and defines WORKGROUP_X, WORKGROUP_Y and VIEW_WINDOWS (1 when the views
// have their own st windows).
// Output: linear RGB, and in alpha the rays that hit.

layout(local_size_x = WORKGROUP_X, local_size_y = WORKGROUP_Y) in;

layout(rgba32f, binding = 0) uniform writeonly image2D frame_image;
layout(binding = 0) uniform sampler2DArray views;       // linear light, bilinear
layout(binding = 1) uniform sampler2DArray depth_maps;  // mm, one layer a view; NaN: unknown
// The views' sRGB codes, undecoded (8-bit light fields; encoded_reads), for the cubic reads.
layout(binding = 2) uniform sampler2DArray views_encoded;

layout(std430, binding = 0) readonly buffer LensPoints { vec4 lens_points[]; };
layout(std430, binding = 1) readonly buffer CameraCentres { vec4 camera_centre[]; };
// Each view's st window: its offset (k, l) from the reference grid in samples.
layout(std430, binding = 2) readonly buffer CameraOffsets { vec2 camera_offset[]; };
layout(std430, binding = 3) readonly buffer HasDepth { int has_depth[]; };

uniform ivec2 frame_size;  // width, height
uniform ivec2 grid;        // camera columns, rows
uniform ivec2 st_size;     // n_s, n_t
// The planes (LightFieldSampler's constants): the uv-plane through the origin (p_ca), its
// normal and its axes scaled to the window; the st-plane's origin, normal and scaled axes, the
// reference grid (s0, t0, s_to_k, t_to_l) and the sampled domain (s lo, t lo, s hi, t hi).
uniform vec3 n_ca, u_scaled, v_scaled;
uniform vec3 st_origin, n_st, s_scaled, t_scaled;
uniform vec4 grid_st;  // s0, t0, s_to_k, t_to_l
uniform vec4 domain;
// The virtual camera: eye, axes, the film's half-angles and principal offset, focus distance.
uniform vec3 eye, cam_u, cam_v, cam_n;
uniform vec2 tan_half, principal_offset;
uniform float focus_distance;
uniform int lens_count;  // 0: a pinhole
uniform bool antialias, cubic_reads, encoded_reads;
// DepthBlend::kAgreeing (render/depth_aware_sampler.h) and its constants.
uniform bool agreeing_blend;
uniform float agreeing_reach, agreement_floor;
// The depth range's ends (inverse depth, 1/mm, widened) and the inverse depth that moves a
// point one sample between neighbouring cameras.
uniform float q_near, q_far, unit_q;

const bool view_windows = VIEW_WINDOWS != 0;

vec3 DirectionThrough(vec2 film) {
  const vec2 x = tan_half * (2.0 * (film - principal_offset) / vec2(frame_size) - 1.0);
  return -cam_n + x.x * cam_u + x.y * cam_v;
}

float DepthOf(vec3 p) { return -dot(n_ca, p); }  // n_ca . (p_ca - p), p_ca the origin

// Where the line from `from` through `to` meets the st-plane, in reference sample coordinates.
bool StSampleAt(vec3 from, vec3 to, out vec2 kl) {
  const vec3 d = to - from;
  const float n = dot(n_st, d);
  kl = vec2(0.0);
  if (n == 0.0) return false;
  const vec3 at = from + (dot(n_st, st_origin - from) / n) * d - st_origin;
  kl = vec2((dot(at, s_scaled) - grid_st.x) * grid_st.z - 0.5,
            (dot(at, t_scaled) - grid_st.y) * grid_st.w - 0.5);
  return true;
}

// Where the lines from `from` through the points a + x b meet the st-plane, as a function of x
// (LightFieldSampler::ProjectLine in C++): kl(x = 1/q) = k0l0 + (kl_a q + kl_b) / (w.x q + w.y).
struct LineProjection {
  vec2 k0l0, kl_a, kl_b, w;
};
LineProjection ProjectLine(vec3 from, vec3 a, vec3 b) {
  const vec3 rel = from - st_origin, a_rel = a - from;
  const float g = -dot(n_st, rel);
  LineProjection line;
  line.k0l0 = vec2((dot(rel, s_scaled) - grid_st.x) * grid_st.z - 0.5,
                   (dot(rel, t_scaled) - grid_st.y) * grid_st.w - 0.5);
  line.kl_a = g * grid_st.zw * vec2(dot(a_rel, s_scaled), dot(a_rel, t_scaled));
  line.kl_b = g * grid_st.zw * vec2(dot(b, s_scaled), dot(b, t_scaled));
  line.w = vec2(dot(n_st, a_rel), dot(n_st, b));
  return line;
}
bool AtReciprocal(LineProjection line, float q, out vec2 kl) {
  const float w = line.w.x * q + line.w.y;
  kl = vec2(0.0);
  if (w == 0.0) return false;
  kl = line.k0l0 + (line.kl_a * q + line.kl_b) / w;
  return true;
}

// Camera c's depth (mm) at the sample nearest to (k, l), or -1 outside its view or unknown.
float DepthAt(int c, vec2 kl) {
  if (has_depth[c] == 0) return -1.0;
  kl -= camera_offset[c];
  if (!(kl.x >= -0.5 && kl.x < float(st_size.x) - 0.5 && kl.y >= -0.5 &&
        kl.y < float(st_size.y) - 0.5))
    return -1.0;
  const ivec2 at = clamp(ivec2(floor(kl + 0.5)), ivec2(0), st_size - 1);
  const float d = texelFetch(depth_maps, ivec3(at, c), 0).r;
  return isnan(d) || isinf(d) || !(d > 0.0) ? -1.0 : d;
}

float Tolerance(float q) { return max(unit_q, 0.015 * q); }

// With views in their own windows: (k, l) moved into view c's window, and whether it lies there.
bool InOwnWindow(int c, inout vec2 kl) {
  if (!view_windows) return true;
  kl -= camera_offset[c];
  return all(greaterThanEqual(kl, vec2(-0.5))) && all(lessThanEqual(kl, vec2(st_size) - 0.5));
}

vec4 KeysWeights(float f) {
  const float a = -0.5;
  const float x0 = 1.0 + f, x1 = f, x2 = 1.0 - f, x3 = 2.0 - f;
  return vec4(((a * x0 - 5.0 * a) * x0 + 8.0 * a) * x0 - 4.0 * a,
              ((a + 2.0) * x1 - (a + 3.0)) * x1 * x1 + 1.0,
              ((a + 2.0) * x2 - (a + 3.0)) * x2 * x2 + 1.0,
              ((a * x3 - 5.0 * a) * x3 + 8.0 * a) * x3 - 4.0 * a);
}

vec3 SrgbToLinear(vec3 e) {
  e = clamp(e, 0.0, 1.0);
  return mix(e / 12.92, pow((e + 0.055) / 1.055, vec3(2.4)), greaterThan(e, vec3(0.04045)));
}

// View c read at its own sample coordinates: bilinearly, or with Keys' cubic over 4 x 4 (an
// 8-bit view's sRGB codes interpolated and the result decoded, as the CPU reads them).
vec3 ReadView(int c, vec2 kl) {
  if (!cubic_reads) return texture(views, vec3((kl + 0.5) / vec2(st_size), float(c))).rgb;
  kl = clamp(kl, vec2(0.0), vec2(st_size - 1));
  const ivec2 base = ivec2(floor(kl));
  const vec4 wk = KeysWeights(kl.x - float(base.x)), wl = KeysWeights(kl.y - float(base.y));
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 4; ++j) {
    const int l = clamp(base.y - 1 + j, 0, st_size.y - 1);
    for (int i = 0; i < 4; ++i) {
      const int k = clamp(base.x - 1 + i, 0, st_size.x - 1);
      const ivec3 at = ivec3(k, l, c);
      sum += wk[i] * wl[j] *
             (encoded_reads ? texelFetch(views_encoded, at, 0).rgb : texelFetch(views, at, 0).rgb);
    }
  }
  return encoded_reads ? SrgbToLinear(sum) : sum;
}

// Whether camera c sees point p (inverse depth q); if so, `rgb` is the view read there.
bool Read(int c, vec3 p, float q, bool want_colour, out vec3 rgb) {
  rgb = vec3(0.0);
  vec2 kl;
  if (!StSampleAt(camera_centre[c].xyz, p, kl)) return false;
  const float d = DepthAt(c, kl);
  if (!(d > 0.0 && abs(1.0 / d - q) <= Tolerance(q))) return false;
  if (want_colour && InOwnWindow(c, kl)) rgb = ReadView(c, kl);
  return true;
}

// The point at inverse depth q on the ray.
vec3 PointAt(vec3 origin, vec3 direction, float origin_depth, float n_dir, float q) {
  return origin + ((origin_depth - 1.0 / q) / n_dir) * direction;
}

// The inverse depth where the ray hits the surface camera c sees, or -1.
float March(int c, vec3 origin, vec3 direction) {
  if (has_depth[c] == 0) return -1.0;  // every step would find no depth
  const float n_dir = dot(n_ca, direction);
  if (n_dir >= 0.0) return -1.0;
  const float origin_depth = DepthOf(origin);
  const float q_a = min(q_near, 1.0 / (max(origin_depth, 0.0) + 1.0)), q_b = q_far;
  if (!(q_a > q_b)) return -1.0;
  // The ray's point at inverse depth q, PointAt(...), is a + (1/q) b: one map for the march.
  const LineProjection line =
      ProjectLine(camera_centre[c].xyz, origin + (origin_depth / n_dir) * direction,
                  (-1.0 / n_dir) * direction);
  vec2 a, b;
  if (!AtReciprocal(line, q_a, a) || !AtReciprocal(line, q_b, b)) return -1.0;
  const float travel = length(b - a);
  const int steps = clamp(int(ceil(max(2.0 * travel, (q_a - q_b) / unit_q))), 4, 2048);
  bool have_previous = false;
  float prev_q = 0.0, prev_g = 0.0, prev_qc = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const float q = q_a + (q_b - q_a) * float(i) / float(steps);
    vec2 kl;
    const float d = AtReciprocal(line, q, kl) ? DepthAt(c, kl) : -1.0;
    if (!(d > 0.0)) {
      have_previous = false;
      continue;
    }
    const float qc = 1.0 / d, g = q - qc;
    if (have_previous) {
      if (prev_g > 0.0 && g <= 0.0 && abs(qc - prev_qc) <= 2.0 * Tolerance(q))
        return prev_q + (q - prev_q) * prev_g / (prev_g - g);
    } else if (abs(g) <= Tolerance(q)) {
      return q;
    }
    have_previous = true;
    prev_q = q;
    prev_g = g;
    prev_qc = qc;
  }
  return -1.0;
}

// The clamped linear interpolation along one axis of n samples (AxisLerp in C++).
void AxisLerp(float x, int n, out int i0, out int i1, out float w1) {
  if (n == 1) {
    i0 = i1 = 0;
    w1 = 0.0;
    return;
  }
  x = clamp(x, 0.0, float(n - 1));
  i0 = min(int(x), n - 2);
  i1 = i0 + 1;
  w1 = x - float(i0);
}

// The four cameras' blend at point p (inverse depth q), mixed with the agreeing cameras' around
// grid position g (columns, rows), every camera read once; false when none of the four sees p:
// DepthAwareSampler::BlendAgreeing.
bool BlendAgreeing(vec3 p, float q, vec2 g, int index[4], float weight[4], int count,
                   out vec3 rgb) {
  rgb = vec3(0.0);
  g = clamp(g, vec2(0.0), vec2(grid - 1));
  // At most 5 x 5 cameras within agreeing_reach (2) steps; those with a tent of zero skipped.
  const ivec2 lo = max(ivec2(ceil(g - agreeing_reach)), ivec2(0));
  const ivec2 hi = min(ivec2(floor(g + agreeing_reach)), grid - 1);
  const int block_cols = hi.x - lo.x + 1, cells = (hi.y - lo.y + 1) * block_cols;
  vec3 colour[25];
  float tent[25];
  bool seen[25];
  for (int r = lo.y; r <= hi.y; ++r)
    for (int c = lo.x; c <= hi.x; ++c) {
      const int cell = (r - lo.y) * block_cols + (c - lo.x);
      tent[cell] = (1.0 - abs(float(r) - g.y) / agreeing_reach) *
                   (1.0 - abs(float(c) - g.x) / agreeing_reach);
      colour[cell] = vec3(0.0);
      seen[cell] = tent[cell] > 0.0 && Read(r * grid.x + c, p, q, true, colour[cell]);
    }
  // The four's reads, from the block (where they always lie: within a step of g).
  bool four_seen[4];
  vec3 four[4];
  vec3 near = vec3(0.0);
  float held = 0.0;
  for (int j = 0; j < count; ++j) {
    const ivec2 at = ivec2(index[j] % grid.x, index[j] / grid.x) - lo;
    const int cell = at.y * block_cols + at.x;
    four_seen[j] = seen[cell];
    four[j] = colour[cell];
    if (four_seen[j]) {
      near += weight[j] * four[j];
      held += weight[j];
    }
  }
  if (!(held > 0.0)) return false;
  near /= held;
  rgb = near;
  const float share = min(1.0, 2.0 * length(g - round(g)));
  if (share <= 0.0) return true;
  float spread = 0.0;
  for (int j = 0; j < count; ++j)
    if (four_seen[j]) spread += weight[j] * dot(four[j] - near, four[j] - near);
  const float s2 = agreement_floor * agreement_floor + spread / held;
  vec3 sum = vec3(0.0);
  float total = 0.0;
  for (int cell = 0; cell < cells; ++cell)
    if (seen[cell]) {
      const vec3 d = colour[cell] - near;
      const float w = tent[cell] * exp(-0.5 * dot(d, d) / s2);
      sum += w * colour[cell];
      total += w;
    }
  if (total > 0.0) rgb = mix(near, sum / total, share);
  return true;
}

// Radiance along the line (origin, direction); false when it misses the slab.
bool Sample(vec3 origin, vec3 direction, out vec3 rgb) {
  rgb = vec3(0.0);
  const float n_uv = dot(n_ca, direction), n_s = dot(n_st, direction);
  if (n_uv == 0.0 || n_s == 0.0) return false;
  const vec3 at_uv = origin + (dot(n_ca, -origin) / n_uv) * direction;
  const vec2 uv = vec2(dot(at_uv, u_scaled), dot(at_uv, v_scaled));
  const vec3 at_st = origin + (dot(n_st, st_origin - origin) / n_s) * direction - st_origin;
  const vec2 st = vec2(dot(at_st, s_scaled), dot(at_st, t_scaled));
  if (!(uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0 && st.x >= domain.x &&
        st.x <= domain.z && st.y >= domain.y && st.y <= domain.w))
    return false;
  int c[2], r[2];
  float wc, wr;
  AxisLerp(uv.x * float(grid.x) - 0.5, grid.x, c[0], c[1], wc);
  AxisLerp(uv.y * float(grid.y) - 0.5, grid.y, r[0], r[1], wr);
  int index[4];
  float weight[4];
  int count = 0;
  const float row_w[2] = float[2](1.0 - wr, wr), col_w[2] = float[2](1.0 - wc, wc);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      if (row_w[a] * col_w[b] > 0.0) {
        index[count] = r[a] * grid.x + c[b];
        weight[count] = row_w[a] * col_w[b];
        ++count;
      }
  // The heaviest camera marches first (DepthAwareSampler::Sample).
  for (int i = 1; i < count; ++i)
    for (int j = i; j > 0 && weight[j] > weight[j - 1]; --j) {
      const int index_j = index[j];
      const float weight_j = weight[j];
      index[j] = index[j - 1];
      weight[j] = weight[j - 1];
      index[j - 1] = index_j;
      weight[j - 1] = weight_j;
    }
  float all = 0.0;
  for (int j = 0; j < count; ++j) all += weight[j];
  const float n_dir = dot(n_ca, direction), origin_depth = DepthOf(origin);
  // Each camera's hit, put to all of them, until one that every camera agrees with.
  float best_q = -1.0, best_support = 0.0;
  vec3 unused;
  for (int i = 0; i < count && !(best_support > all - 1e-6); ++i) {
    const float q = March(index[i], origin, direction);
    if (q <= 0.0) continue;
    const vec3 p = PointAt(origin, direction, origin_depth, n_dir, q);
    float support = 0.0;
    for (int j = 0; j < count; ++j)
      if (Read(index[j], p, q, false, unused)) support += weight[j];
    if (support > best_support + 1e-6 || (support > best_support - 1e-6 && q > best_q)) {
      best_support = support;
      best_q = q;
    }
  }
  if (best_q > 0.0) {
    const vec3 p = PointAt(origin, direction, origin_depth, n_dir, best_q);
    if (agreeing_blend) {
      if (BlendAgreeing(p, best_q, uv * vec2(grid) - 0.5, index, weight, count, rgb)) return true;
    } else {
      vec3 acc = vec3(0.0);
      float total = 0.0;
      for (int j = 0; j < count; ++j) {
        vec3 read;
        if (Read(index[j], p, best_q, true, read)) {
          acc += weight[j] * read;
          total += weight[j];
        }
      }
      if (total > 0.0) {
        rgb = acc / total;
        return true;
      }
    }
  }
  // No depth found: the paper's lookup at the ray's own (u, v, s, t).
  const vec2 kl = vec2((st.x - grid_st.x) * grid_st.z - 0.5, (st.y - grid_st.y) * grid_st.w - 0.5);
  vec3 acc = vec3(0.0);
  float held = 0.0;
  for (int j = 0; j < count; ++j) {
    vec2 local = kl;
    if (!InOwnWindow(index[j], local)) continue;
    acc += weight[j] * texture(views, vec3((local + 0.5) / vec2(st_size), float(index[j]))).rgb;
    held += weight[j];
  }
  if (!view_windows) {
    rgb = acc;
    return true;
  }
  rgb = held > 0.0 ? acc / held : vec3(0.0);
  return held > 0.0;
}

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, frame_size))) return;
  vec3 sum = vec3(0.0), rgb;
  int hits = 0;
  if (antialias) {
    // Rays over the pixel's area as well as the lens (RenderPixelDepth): a pinhole's 2 x 2 film
    // points; lens sample m at film point m of the R2 sequence.
    if (lens_count == 0) {
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          if (Sample(eye,
                     DirectionThrough(vec2(pixel) +
                                      vec2(0.25 + 0.5 * float(b), 0.25 + 0.5 * float(a))),
                     rgb)) {
            sum += rgb;
            ++hits;
          }
    } else {
      for (int m = 0; m < lens_count; ++m) {
        const vec2 film = vec2(fract(0.5 + 0.7548776662466927 * float(m)),
                               fract(0.5 + 0.5698402909980532 * float(m)));
        const vec3 p_o = eye + focus_distance * DirectionThrough(vec2(pixel) + film);
        const vec3 lens = lens_points[m].xyz;
        if (Sample(lens, p_o - lens, rgb)) {
          sum += rgb;
          ++hits;
        }
      }
    }
  } else {
    const vec3 direction = DirectionThrough(vec2(pixel) + 0.5);
    if (lens_count == 0) {
      if (Sample(eye, direction, rgb)) {
        sum = rgb;
        hits = 1;
      }
    } else {
      const vec3 p_o = eye + focus_distance * direction;
      for (int m = 0; m < lens_count; ++m) {
        const vec3 lens = lens_points[m].xyz;
        if (Sample(lens, p_o - lens, rgb)) {
          sum += rgb;
          ++hits;
        }
      }
    }
  }
  imageStore(frame_image, pixel, vec4(hits > 0 ? sum / float(hits) : vec3(0.0), float(hits)));
}
