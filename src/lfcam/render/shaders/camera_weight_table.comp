// The cameras integrator's weight table on the GPU, for a frame whose footprints differ from pixel
// to pixel (the eye off the array's plane, or a turned camera): what CameraIntegratorFrame
// builds on the CPU, in three passes (PASS):
//   0  the range of the frame's footprints: one invocation a pixel, atomic min and max of the
//      radius and the centre (floats as order-preserving integers), read back by the C++ side,
//      which lays the table out (CameraIntegratorFrame::TableLayout);
//   1  the table: one invocation an entry (radius level, lattice node, camera), the exact
//      integral of the camera's weight function over the disk (render/aperture_weights.cpp's
//      DiskCameraIntegral, in float);
//   2  each node's weights normalised to sum to 1 (all 0 when the disk misses the window).
// The C++ side prepends "#version 430 core", PASS, and camera_footprint.comp.

#if PASS == 0
layout(local_size_x = 16, local_size_y = 8) in;
layout(std430, binding = 0) buffer Range { int range[6]; };  // r lo, r hi, x lo, x hi, y lo, y hi
uniform ivec2 frame_size;
uniform ivec2 grid;  // camera columns, rows

// A float as an integer of the same order.
int Ordered(float v) {
  const int bits = floatBitsToInt(v);
  return bits >= 0 ? bits : bits ^ 0x7fffffff;
}

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, frame_size))) return;
  vec3 f;
  if (!Footprint(pixel, f) || any(isnan(f)) || any(isinf(f))) return;
  // Centres farther than the radius plus a pitch from the window have no weights.
  if (f.x < -1.5 - f.z || f.x > float(grid.x) + 0.5 + f.z || f.y < -1.5 - f.z ||
      f.y > float(grid.y) + 0.5 + f.z)
    return;
  atomicMin(range[0], Ordered(f.z));
  atomicMax(range[1], Ordered(f.z));
  atomicMin(range[2], Ordered(f.x));
  atomicMax(range[3], Ordered(f.x));
  atomicMin(range[4], Ordered(f.y));
  atomicMax(range[5], Ordered(f.y));
}

#else
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Table { float table[]; };
uniform ivec2 grid;     // camera columns, rows
uniform ivec4 lattice;  // x0, y0, nx, ny: node (a, b) at ((x0 + a), (y0 + b)) / nodes_per_pitch
uniform int nodes_per_pitch, level_count;
uniform float radius0, radius_step;
uniform uint entries;  // invocations with work: entries of the table (1) or nodes (2)

uint Invocation() {
  return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x +
         gl_LocalInvocationID.x;
}

#if PASS == 1
const float kPi = 3.14159265358979;

// Camera i's weight at x along one axis of an n-camera grid: the bilinear lookup's tent, held at
// 1 out to the window's edge for the outermost cameras, nothing outside the window.
float AxisWeight(float x, int i, int n) {
  if (x < -0.5 || x > float(n) - 0.5) return 0.0;
  if (n == 1) return 1.0;
  if ((i == 0 && x <= 0.0) || (i == n - 1 && x >= float(n - 1))) return 1.0;
  return max(0.0, 1.0 - abs(x - float(i)));
}

// Where AxisWeight(., i, n) has a kink or a jump, sorted. (The sorts here run over whole arrays
// with fixed bounds: no loop condition reads an element, which a compiler may read early.)
float[7] AxisKinks(int i, int n) {
  float k[7] =
      float[7](-0.5, float(n) - 0.5, float(i) - 1.0, float(i), float(i) + 1.0, 0.0, float(n - 1));
  for (int a = 0; a < 7; ++a) k[a] = clamp(k[a], -0.5, float(n) - 0.5);
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6 - a; ++b)
      if (k[b] > k[b + 1]) {
        const float t = k[b];
        k[b] = k[b + 1];
        k[b + 1] = t;
      }
  return k;
}

// The integral of AxisWeight(., i, n) from -infinity to y (linear between kinks: the midpoint
// rule is exact).
float AxisCumulative(float y, int i, int n, float kinks[7]) {
  float sum = 0.0;
  for (int p = 0; p + 1 < 7; ++p) {
    const float a = kinks[p], b = min(kinks[p + 1], y);
    if (b <= a) continue;
    sum += (b - a) * AxisWeight(0.5 * (a + b), i, n);
  }
  return sum;
}

// The integral over the disk of `radius` centred at (cx, cy) of camera (col, row)'s weight
// function: the disk swept along x = cx + R sin(theta), the integral along y closed form, theta
// split at every kink, 8-point Gauss-Legendre on each piece.
float DiskCameraIntegral(float radius, float cx, float cy, int col, int row) {
  if (!(radius > 0.0)) return 0.0;
  const float xk[7] = AxisKinks(col, grid.x), yk[7] = AxisKinks(row, grid.y);
  // The cuts, the unused entries past every angle (sorted to the end).
  float cuts[23];
  for (int a = 0; a < 23; ++a) cuts[a] = 10.0;
  int n = 2;
  cuts[0] = -0.5 * kPi;
  cuts[1] = 0.5 * kPi;
  for (int a = 0; a < 7; ++a)
    if (abs(xk[a] - cx) < radius) {
      cuts[n] = asin(clamp((xk[a] - cx) / radius, -1.0, 1.0));
      n += 1;
    }
  for (int a = 0; a < 7; ++a)
    if (abs(yk[a] - cy) < radius) {
      const float theta = acos(clamp(abs(yk[a] - cy) / radius, 0.0, 1.0));
      cuts[n] = theta;
      cuts[n + 1] = -theta;
      n += 2;
    }
  for (int a = 0; a < 22; ++a)
    for (int b = 0; b < 22 - a; ++b)
      if (cuts[b] > cuts[b + 1]) {
        const float t = cuts[b];
        cuts[b] = cuts[b + 1];
        cuts[b + 1] = t;
      }
  const float nodes[4] =
      float[4](0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363);
  const float weights[4] =
      float[4](0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763);
  float sum = 0.0;
  for (int p = 0; p + 1 < n; ++p) {
    const float mid = 0.5 * (cuts[p] + cuts[p + 1]), half_width = 0.5 * (cuts[p + 1] - cuts[p]);
    if (half_width <= 0.0) continue;
    float piece = 0.0;
    for (int q = 0; q < 8; ++q) {
      const float theta = mid + (q < 4 ? -half_width : half_width) * nodes[q % 4];
      const float x = cx + radius * sin(theta), h = radius * cos(theta);
      const float wx = AxisWeight(x, col, grid.x);
      if (wx == 0.0) continue;
      const float wy =
          AxisCumulative(cy + h, row, grid.y, yk) - AxisCumulative(cy - h, row, grid.y, yk);
      piece += weights[q % 4] * wx * wy * h;
    }
    sum += half_width * piece;
  }
  return sum;
}

void main() {
  const uint id = Invocation();
  if (id >= entries) return;
  const uint cameras = uint(grid.x * grid.y), nodes = uint(lattice.z * lattice.w);
  const int camera = int(id % cameras), node = int((id / cameras) % nodes);
  const int level = int(id / (cameras * nodes));
  const float cx = float(lattice.x + node % lattice.z) / float(nodes_per_pitch);
  const float cy = float(lattice.y + node / lattice.z) / float(nodes_per_pitch);
  const float radius = radius0 + float(level) * radius_step;
  const int col = camera % grid.x, row = camera / grid.x;
  // Cameras beyond the radius and a pitch have no share (as DiskCameraWeights skips them).
  const float reach = max(radius, 0.0) + 1.0;
  float w = 0.0;
  if (abs(float(col) - cx) <= reach + 1.0 && abs(float(row) - cy) <= reach + 1.0)
    w = radius > 0.0 ? DiskCameraIntegral(radius, cx, cy, col, row)
                     : AxisWeight(cx, col, grid.x) * AxisWeight(cy, row, grid.y);
  table[id] = w;
}

#else  // PASS == 2
void main() {
  const uint node = Invocation();
  if (node >= entries) return;
  const uint cameras = uint(grid.x * grid.y), base = node * cameras;
  float total = 0.0;
  for (uint c = 0u; c < cameras; ++c) total += table[base + c];
  const float scale = total > 0.0 ? 1.0 / total : 0.0;
  for (uint c = 0u; c < cameras; ++c) table[base + c] *= scale;
}
#endif
#endif
