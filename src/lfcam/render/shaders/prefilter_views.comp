// The quadrilinear limit's prefilter on the GPU (render/quadrilinear_limit.h): the views filtered
// along one axis by symmetric taps, in linear light, each view's edges replicated. Run twice, along
// s and then along t; the second pass reads the first's output. One invocation a sample of one
// view (z: the index into `layers`, the views some pixel of the frame reads).
//
// The C++ side prepends "#version 430 core".

layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = 0) uniform sampler2DArray source;  // linear light (an sRGB array decodes)
layout(rgba16f, binding = 0) uniform writeonly image2DArray target;
layout(std430, binding = 0) readonly buffer Taps { float taps[]; };
layout(std430, binding = 1) readonly buffer Layers { int layers[]; };

uniform ivec2 size;     // n_s, n_t
uniform ivec2 axis;     // (1, 0) along s, (0, 1) along t
uniform int tap_count;  // odd: taps[tap_count / 2] is the centre's

void main() {
  const ivec2 at = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(at, size))) return;
  const int layer = layers[gl_GlobalInvocationID.z];
  const int reach = tap_count / 2;
  vec3 sum = vec3(0.0);
  for (int i = 0; i < tap_count; ++i) {
    const ivec2 p = clamp(at + (i - reach) * axis, ivec2(0), size - 1);
    sum += taps[i] * texelFetch(source, ivec3(p, layer), 0).rgb;
  }
  imageStore(target, ivec3(at, layer), vec4(sum, 1.0));
}
