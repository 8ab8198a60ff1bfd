// One frame of the light field renderer, one invocation a pixel: the GL twin of the CPU
// renderer's row kernels (render/simd_kernels.cpp), over the per-frame set-up both share
// (render/ray_setup.h): every coordinate is a projective function of the pixel, from constants
// computed once per frame in C++. The views are an sRGB texture array, one layer a view: the
// hardware decodes to linear light and filters bilinearly within a view; the blend across
// cameras is taken here.
//
// The C++ side prepends "#version 430 core" and defines WORKGROUP_X, WORKGROUP_Y, VIEW_WINDOWS
// (1 when the views have their own st windows: a compile-time switch, so that a shared grid pays
// nothing for it) and MODE:
//   MODE 0  lens samples, the paper's quadrilinear lookup
//   MODE 1  lens samples, the focal-plane lookup
//   MODE 2  the cameras integrator, one weight list for every pixel
//   MODE 3  the cameras integrator, weights per pixel from the frame's table
// Output: linear RGB, and in alpha the rays that hit (lens samples) or the cameras read.

layout(local_size_x = WORKGROUP_X, local_size_y = WORKGROUP_Y) in;

layout(rgba32f, binding = 0) uniform writeonly image2D frame_image;
layout(binding = 0) uniform sampler2DArray views;

// An origin's constants against a plane (OriginConstants in ray_setup.h).
struct Origin {
  float num, n_o, x_o, y_o, x0, y0;
};
layout(std430, binding = 0) readonly buffer LensUv { Origin lens_uv[]; };
layout(std430, binding = 1) readonly buffer LensSt { Origin lens_st[]; };
layout(std430, binding = 2) readonly buffer CameraSt { Origin camera_st[]; };
struct CameraWeight {
  int index;
  float weight;
};
layout(std430, binding = 3) readonly buffer CameraWeights { CameraWeight camera_weights[]; };
layout(std430, binding = 4) readonly buffer WeightTable { float weight_table[]; };
// Each view's st window: its offset (k, l) from the reference grid in samples.
layout(std430, binding = 5) readonly buffer CameraOffsets { vec2 camera_offset[]; };

uniform ivec2 frame_size;  // width, height
uniform ivec2 grid;        // camera columns, rows
uniform ivec2 st_size;     // n_s, n_t
// The sampled st domain in reference samples (lo k, lo l, hi k, hi l: the union of the views'
// windows). With VIEW_WINDOWS a read outside a view's window adds nothing and the blend
// renormalises over the views that hold the point (RaySetup).
uniform vec4 st_domain;
const bool view_windows = VIEW_WINDOWS != 0;
// The cameras integrators: the quadrilinear limit's fade at the views' windows, the half-widths
// (samples) of each camera's tent on the st-plane; (0, 0): the hard edges of the focal-plane
// reads (render/window_taper.h).
uniform vec2 window_taper;
// p_o against the uv- and st-planes: (n.p_o, a_x.p_o, a_y.p_o) = at00 + di * i + dj * j.
uniform vec3 uv_at00, uv_di, uv_dj, st_at00, st_di, st_dj;
uniform int lens_count;
uniform int weight_count;
// MODE 3: the table (CameraIntegratorFrame's lattice of footprint centres, per radius level);
// the footprint's set-up is camera_footprint.comp's, which the C++ side puts before this.
uniform int level_count, nodes_per_pitch;
uniform ivec4 lattice;  // x0, y0, nx, ny
uniform float radius0, radius_step;

struct Hit {
  vec2 at;
  bool valid;
};

// Where the line from an origin through p_o (as plane functions p) meets the plane.
Hit Project(vec3 p, Origin o) {
  Hit h;
  const float den = p.x - o.n_o;
  h.valid = den != 0.0;
  const float lambda = o.num / (h.valid ? den : 1.0);
  h.at = vec2(fma(lambda, p.y - o.x_o, o.x0), fma(lambda, p.z - o.y_o, o.y0));
  if (!h.valid) h.at = vec2(0.0);
  return h;
}

bool Inside(Hit h, ivec2 n) {
  return h.valid && all(greaterThanEqual(h.at, vec2(-0.5))) &&
         all(lessThanEqual(h.at, vec2(n) - 0.5));
}

bool InsideDomain(Hit h) {
  return h.valid && all(greaterThanEqual(h.at, st_domain.xy)) &&
         all(lessThanEqual(h.at, st_domain.zw));
}

// The weight a read at a view's own sample coordinates carries: 1, or with views' own windows 0
// outside the view's window.
float Held(Hit local) { return !view_windows || Inside(local, st_size) ? 1.0 : 0.0; }

// The clamped linear interpolation along one axis of n samples (AxisLerp in C++).
void AxisLerp(float x, int n, out int i0, out int i1, out float w1) {
  x = clamp(x, 0.0, float(n - 1));
  i0 = clamp(int(x), 0, max(n - 2, 0));
  i1 = min(i0 + 1, n - 1);
  w1 = x - float(i0);
}

// View `layer` read bilinearly at st sample coordinates (k, l), in linear light.
vec3 ReadView(int layer, vec2 kl) {
  return texture(views, vec3((kl + 0.5) / vec2(st_size), float(layer))).rgb;
}

// Camera `index` read along its own line through p_o (the focal-plane read), and in alpha the
// weight the read carries (Held).
vec4 ReadFocused(int index, vec3 p_st) {
  const Hit h = Project(p_st, camera_st[index]);
  const float held = Held(h);
  return vec4(h.valid && held > 0.0 ? ReadView(index, h.at) : vec3(0.0), held);
}

// The share of a tent of half-width h centred at x inside [lo, hi] (TentShareInside in C++; h 0:
// the hard edge).
float TentShare(float x, float lo, float hi, float h) {
  if (!(h > 0.0)) return x >= lo && x <= hi ? 1.0 : 0.0;
  const float a = clamp((hi - x) / h, -1.0, 1.0), b = clamp((x - lo) / h, -1.0, 1.0);
  return max(0.0, (0.5 + a - 0.5 * a * abs(a)) + (0.5 + b - 0.5 * b * abs(b)) - 1.0);
}

// The cameras integrator's read of camera `index`: as ReadFocused where the camera's own line
// through p_o meets the sampled st domain, else nothing and no weight (a camera counts where its
// line does, as a lens sample does; RenderPixelCameras in C++). With a taper, by the share of its
// tent inside its view's window (the domain where the views share it), the read weighted by it.
vec4 ReadCounted(int index, vec3 p_st) {
  if (window_taper.x > 0.0 || window_taper.y > 0.0) {
    const Hit h = Project(p_st, camera_st[index]);
    const vec2 hi = vec2(st_size) - 0.5;
    const float share = h.valid ? TentShare(h.at.x, -0.5, hi.x, window_taper.x) *
                                      TentShare(h.at.y, -0.5, hi.y, window_taper.y)
                                : 0.0;
    return share > 0.0 ? vec4(share * ReadView(index, h.at), share) : vec4(0.0);
  }
  if (!InsideDomain(Project(p_st, camera_st[index]))) return vec4(0.0);
  return ReadFocused(index, p_st);
}

// Camera `index` read at the ray's own st point (reference samples; the paper's lookup), the
// weight in alpha.
vec4 ReadAt(int index, Hit at_st) {
  if (!view_windows) return vec4(ReadView(index, at_st.at), 1.0);
  Hit local = at_st;
  local.at -= camera_offset[index];
  const float held = Held(local);
  return vec4(held > 0.0 ? ReadView(index, local.at) : vec3(0.0), held);
}

#if MODE == 3
// The table's weight of camera `index` for a footprint centred at (cx, cy) at radius level
// `level`: bilinear between the four lattice nodes around the centre.
float LevelWeight(int level, int index, float cx, float cy) {
  const float x = cx * float(nodes_per_pitch) - float(lattice.x);
  const float y = cy * float(nodes_per_pitch) - float(lattice.y);
  const int a = int(floor(x)), b = int(floor(y));
  const float fx = x - float(a), fy = y - float(b);
  const int cameras = grid.x * grid.y;
  const int a0 = clamp(a, 0, lattice.z - 1), a1 = clamp(a + 1, 0, lattice.z - 1);
  const int b0 = clamp(b, 0, lattice.w - 1), b1 = clamp(b + 1, 0, lattice.w - 1);
  const int base = level * lattice.z * lattice.w;
  const float w00 = weight_table[((base + b0 * lattice.z + a0) * cameras) + index];
  const float w10 = weight_table[((base + b0 * lattice.z + a1) * cameras) + index];
  const float w01 = weight_table[((base + b1 * lattice.z + a0) * cameras) + index];
  const float w11 = weight_table[((base + b1 * lattice.z + a1) * cameras) + index];
  return (1.0 - fy) * ((1.0 - fx) * w00 + fx * w10) + fy * ((1.0 - fx) * w01 + fx * w11);
}

// The cameras integrator with a footprint per pixel (CameraIntegratorFrame::FootprintOf and
// Weights in C++).
void RenderCamerasTable(ivec2 pixel, vec3 p_st, out vec3 sum, out int reads) {
  sum = vec3(0.0);
  reads = 0;
  vec3 footprint;
  if (!Footprint(pixel, footprint)) return;
  const float cx = footprint.x, cy = footprint.y, radius = footprint.z;
  // A footprint that does not meet the window has no weights.
  const float dx = max(max(-0.5 - cx, cx - (float(grid.x) - 0.5)), 0.0);
  const float dy = max(max(-0.5 - cy, cy - (float(grid.y) - 0.5)), 0.0);
  if (dx * dx + dy * dy >= radius * radius && (dx > 0.0 || dy > 0.0)) return;
  int k = 0;
  float t = 0.0;
  if (level_count > 1) {
    const float x = clamp((radius - radius0) / radius_step, 0.0, float(level_count - 1));
    k = min(int(x), level_count - 2);
    t = x - float(k);
  }
  // Only the cameras the footprint (with the lattice's and the levels' slack) can reach.
  const float reach = radius + 1.5;
  const int c0 = max(int(floor(cx - reach)), 0), c1 = min(int(ceil(cx + reach)), grid.x - 1);
  const int r0 = max(int(floor(cy - reach)), 0), r1 = min(int(ceil(cy + reach)), grid.y - 1);
  float total = 0.0;
  for (int row = r0; row <= r1; ++row)
    for (int col = c0; col <= c1; ++col) {
      const int index = row * grid.x + col;
      float w = LevelWeight(k, index, cx, cy);
      if (level_count > 1) w = (1.0 - t) * w + t * LevelWeight(k + 1, index, cx, cy);
      if (!(w > 0.0)) continue;
      const vec4 read = ReadCounted(index, p_st);
      if (!(read.a > 0.0)) continue;
      total += w * read.a;
      sum += w * read.rgb;
      ++reads;
    }
  // The counted cameras' weights renormalised to the whole.
  if (total > 0.0)
    sum /= total;
  else
    reads = 0;
}
#endif

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, frame_size))) return;
  const vec2 ij = vec2(pixel);
  const vec3 p_st = st_at00 + st_di * ij.x + st_dj * ij.y;
  vec3 sum = vec3(0.0);
  int count = 0;
#if MODE == 0 || MODE == 1
  const vec3 p_uv = uv_at00 + uv_di * ij.x + uv_dj * ij.y;
  for (int n = 0; n < lens_count; ++n) {
    const Hit at_uv = Project(p_uv, lens_uv[n]);
    const Hit at_st = Project(p_st, lens_st[n]);
    if (!Inside(at_uv, grid) || !InsideDomain(at_st)) continue;
    int c[2], r[2];
    float wc, wr;
    AxisLerp(at_uv.at.x, grid.x, c[0], c[1], wc);
    AxisLerp(at_uv.at.y, grid.y, r[0], r[1], wr);
    const float row_w[2] = float[2](1.0 - wr, wr), col_w[2] = float[2](1.0 - wc, wc);
#if VIEW_WINDOWS
    vec3 one = vec3(0.0);
    float held = 0.0;
#else
    ++count;
#endif
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const float w = row_w[a] * col_w[b];
        if (w == 0.0) continue;
        const int index = r[a] * grid.x + c[b];
#if MODE == 0
        const vec4 read = ReadAt(index, at_st);
#else
        const vec4 read = ReadFocused(index, p_st);
#endif
#if VIEW_WINDOWS
        one += w * read.rgb;
        held += w * read.a;
#else
        sum += w * read.rgb;
#endif
      }
#if VIEW_WINDOWS
    // The lens sample's blend renormalised over the cameras that hold its point; a sample none
    // holds misses.
    if (held > 0.0) {
      sum += one / held;
      ++count;
    }
#endif
  }
  if (count > 0) sum /= float(count);
#else
#if MODE == 2
  float held = 0.0;
  for (int n = 0; n < weight_count; ++n) {
    const vec4 read = ReadCounted(camera_weights[n].index, p_st);
    sum += camera_weights[n].weight * read.rgb;
    held += camera_weights[n].weight * read.a;
    if (read.a > 0.0) ++count;
  }
  // The counted cameras' weights renormalised to the whole.
  sum = held > 0.0 ? sum / held : vec3(0.0);
  if (!(held > 0.0)) count = 0;
#else
  RenderCamerasTable(pixel, p_st, sum, count);
#endif
#endif
  imageStore(frame_image, pixel, vec4(sum, float(count)));
}
