#include "lfcam/render/gl_renderer.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/gpu/gl_program.h"
#include "lfcam/render/camera_integrator.h"
#include "lfcam/render/depth_aware_sampler.h"
#include "lfcam/render/quadrilinear_limit.h"
#include "lfcam/render/ray_setup.h"
#include "lfcam/render/shaders/camera_footprint.comp.h"
#include "lfcam/render/shaders/camera_weight_table.comp.h"
#include "lfcam/render/shaders/prefilter_views.comp.h"
#include "lfcam/render/shaders/render_depth.comp.h"
#include "lfcam/render/shaders/render_frame.comp.h"

namespace lfcam {
namespace {

// The shader's modes (render_frame.comp).
enum Mode { kLensQuadrilinear = 0, kLensFocalPlane = 1, kCamerasUniform = 2, kCamerasTable = 3 };

// The buffers' binding points in the shader.
enum Binding {
  kLensUv = 0,
  kLensSt = 1,
  kCameraSt = 2,
  kCameraWeights = 3,
  kWeightTable = 4,
  kCameraOffsets = 5,
  kBindings = 6
};

struct ShaderCameraWeight {
  std::int32_t index;
  float weight;
};
static_assert(sizeof(OriginConstants) == 6 * sizeof(float), "std430 layout of Origin");

// Uniform setters by name (a name the compiler optimised away is skipped).
struct Uniforms {
  GLuint program;
  GLint At(const char* name) const { return glGetUniformLocation(program, name); }
  void Int(const char* name, int v) const { glUniform1i(At(name), v); }
  void Float(const char* name, double v) const { glUniform1f(At(name), float(v)); }
  void Int2(const char* name, int a, int b) const { glUniform2i(At(name), a, b); }
  void Int4(const char* name, int a, int b, int c, int d) const {
    glUniform4i(At(name), a, b, c, d);
  }
  void Vec3f(const char* name, const Vec3& v) const {
    glUniform3f(At(name), float(v.x()), float(v.y()), float(v.z()));
  }
  void Vec3f(const char* name, double x, double y, double z) const {
    glUniform3f(At(name), float(x), float(y), float(z));
  }
  // A plane's three functions of p_o: at00, di, dj as (n, x, y).
  void Plane(const char* prefix, const PlaneAffines& p) const {
    Vec3f(fmt::format("{}_at00", prefix).c_str(), p.n.at00, p.x.at00, p.y.at00);
    Vec3f(fmt::format("{}_di", prefix).c_str(), p.n.di, p.x.di, p.y.di);
    Vec3f(fmt::format("{}_dj", prefix).c_str(), p.n.dj, p.x.dj, p.y.dj);
  }
  void Origin(const char* prefix, const OriginConstants& o) const {
    const std::string p(prefix);
    glUniform1f(At((p + ".num").c_str()), o.num);
    glUniform1f(At((p + ".n_o").c_str()), o.n_o);
    glUniform1f(At((p + ".x_o").c_str()), o.x_o);
    glUniform1f(At((p + ".y_o").c_str()), o.y_o);
    glUniform1f(At((p + ".x0").c_str()), o.x0);
    glUniform1f(At((p + ".y0").c_str()), o.y0);
  }
};

template <typename T>
void FillBuffer(GLuint buffer, const std::vector<T>& data) {
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  // An empty buffer still gets a few bytes: a binding needs storage.
  const std::size_t bytes = std::max<std::size_t>(data.size() * sizeof(T), 16);
  glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, GL_STREAM_DRAW);
  if (!data.empty())
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(data.size() * sizeof(T)), data.data());
}

std::string Mib(double bytes) { return fmt::format("{:.0f} MiB", bytes / (1024.0 * 1024.0)); }

// The footprints' set-up (camera_footprint.comp).
void FootprintUniforms(const Uniforms& u, const LightField& lf, const VirtualCamera& camera) {
  const ArrayPlane& array = lf.slab().uv;
  const Vec3 p00 = camera.focus_point(camera.pixel_direction(0, 0));
  u.Vec3f("focus_at00", p00 - array.p_ca);
  u.Vec3f("focus_di", camera.focus_point(camera.pixel_direction(1, 0)) - p00);
  u.Vec3f("focus_dj", camera.focus_point(camera.pixel_direction(0, 1)) - p00);
  u.Vec3f("eye_from_array", camera.e_c() - array.p_ca);
  u.Vec3f("array_u", array.u_ca);
  u.Vec3f("array_v", array.v_ca);
  u.Vec3f("array_n", array.n_ca);
  u.Vec3f("lens_u", camera.u_c());
  u.Vec3f("lens_v", camera.v_c());
  u.Float("pitch_mm", array.pitch_mm);
  u.Float("lens_radius_mm", 0.5 * camera.params().aperture_mm);
}

// The weight table's layout (render_frame.comp's MODE 3, camera_weight_table.comp).
void TableUniforms(const Uniforms& u, const std::vector<CameraIntegratorFrame::Level>& levels) {
  u.Int("level_count", int(levels.size()));
  u.Int("nodes_per_pitch", CameraIntegratorFrame::kNodesPerPitch);
  u.Int4("lattice", levels[0].x0, levels[0].y0, levels[0].nx, levels[0].ny);
  u.Float("radius0", levels[0].radius);
  u.Float("radius_step", levels.size() > 1 ? levels[1].radius - levels[0].radius : 1.0);
}

}  // namespace

GlRenderer::GlRenderer(bool prefer_hardware) : GlRenderer(GlContext::Create(prefer_hardware)) {}

GlRenderer::GlRenderer(std::unique_ptr<GlContext> context) : context_(std::move(context)) {
  GLint v = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &v);
  limits_.max_texture_size = v;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &v);
  limits_.max_array_layers = v;
  glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &v);
  limits_.max_workgroup_invocations = v;
  GLint64 block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  limits_.max_storage_block_bytes = block;
  if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
    glGetIntegerv(GL_GPU_MEMORY_INFO_DEDICATED_VIDMEM_NVX, &v);
    limits_.dedicated_memory_kb = v;
  }
  glGenBuffers(kBindings, buffers_);
  glGenBuffers(2, prefilter_buffers_);
  glGenBuffers(1, &range_buffer_);
  glGenQueries(1, &timer_);
  CheckGl("setting up the renderer");
}

GlRenderer::~GlRenderer() {
  try {
    context_->MakeCurrent();
  } catch (const Error&) {
    return;  // the context goes with its objects
  }
  for (const auto& [key, program] : programs_) glDeleteProgram(program);
  glDeleteBuffers(kBindings, buffers_);
  glDeleteBuffers(2, prefilter_buffers_);
  glDeleteBuffers(1, &range_buffer_);
  glDeleteTextures(2, filtered_);
  glDeleteQueries(1, &timer_);
  if (views_encoded_) glDeleteTextures(1, &views_encoded_);
  if (views_) glDeleteTextures(1, &views_);
  if (output_) glDeleteTextures(1, &output_);
  if (depth_maps_) glDeleteTextures(1, &depth_maps_);
}

void GlRenderer::RequireGpuMemory(double bytes, const std::string& what) const {
  if (limits_.dedicated_memory_kb > 0 && bytes > 1024.0 * double(limits_.dedicated_memory_kb))
    throw Error(fmt::format("{}: about {} on the GPU, and {} has {}", what, Mib(bytes),
                            device().renderer, Mib(1024.0 * double(limits_.dedicated_memory_kb))));
}

unsigned GlRenderer::NewTextureArray(unsigned format, const LightFieldDims& d, int filter,
                                     double bytes, const std::string& what) {
  while (glGetError() != GL_NO_ERROR) {
  }
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, format, d.n_s, d.n_t, GLsizei(d.view_count()));
  if (glGetError() == GL_OUT_OF_MEMORY) {
    glDeleteTextures(1, &texture);
    throw Error(fmt::format("{} ({}): more than the memory of {} holds", what, Mib(bytes),
                            device().renderer));
  }
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

void GlRenderer::Upload(const LightField& lf) {
  const LightFieldDims& d = lf.dims();
  if (views_ && uploaded_ == lf.data() && uploaded_serial_ == lf.samples_serial() &&
      uploaded_dims_ == d)
    return;
  if (d.n_s > limits_.max_texture_size || d.n_t > limits_.max_texture_size)
    throw Error(fmt::format(
        "the light field's views ({}x{} samples) exceed this GPU's largest texture ({} on {})",
        d.n_s, d.n_t, limits_.max_texture_size, device().renderer));
  if (static_cast<long long>(d.view_count()) > limits_.max_array_layers)
    throw Error(
        fmt::format("the light field's {} views exceed this GPU's texture array layers ({} on {})",
                    d.view_count(), limits_.max_array_layers, device().renderer));
  const bool srgb8 = lf.sample_type() == SampleType::kSrgb8;
  // The driver may pad each texel to four channels.
  const double bytes = double(d.samples_per_view()) * double(d.view_count()) * (srgb8 ? 4 : 8);
  // Another light field of the same shape (a video's next frame): the texture is kept, its
  // samples replaced.
  const bool reuse = views_ && uploaded_dims_ == d && uploaded_srgb8_ == srgb8;
  uploaded_ = nullptr;
  uploaded_serial_ = 0;
  if (!reuse) {
    RequireGpuMemory(bytes, "the light field");
    if (views_encoded_) glDeleteTextures(1, &views_encoded_);
    if (views_) glDeleteTextures(1, &views_);
    views_ = views_encoded_ = 0;
    views_ = NewTextureArray(srgb8 ? GL_SRGB8 : GL_RGB16F, d, GL_LINEAR, bytes, "the light field");
    if (srgb8) {
      glGenTextures(1, &views_encoded_);
      glTextureView(views_encoded_, GL_TEXTURE_2D_ARRAY, views_, GL_RGB8, 0, 1, 0,
                    GLuint(d.view_count()));
      glBindTexture(GL_TEXTURE_2D_ARRAY, views_encoded_);
      glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glBindTexture(GL_TEXTURE_2D_ARRAY, views_);
    }
  } else {
    glBindTexture(GL_TEXTURE_2D_ARRAY, views_);
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (std::size_t v = 0; v < d.view_count(); ++v)
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, GLint(v), d.n_s, d.n_t, 1, GL_RGB,
                    srgb8 ? GL_UNSIGNED_BYTE : GL_HALF_FLOAT, lf.data() + v * lf.view_bytes());
  CheckGl("uploading the light field");
  uploaded_ = lf.data();
  uploaded_serial_ = lf.samples_serial();
  uploaded_dims_ = d;
  uploaded_srgb8_ = srgb8;
}

unsigned GlRenderer::Program(int mode, bool view_windows, const GlRenderOptions& options) {
  const std::string defines = fmt::format(
      "#define WORKGROUP_X {}\n#define WORKGROUP_Y {}\n#define MODE {}\n#define VIEW_WINDOWS {}\n",
      options.workgroup_x, options.workgroup_y, mode, view_windows ? 1 : 0);
  auto& program = programs_[defines];
  // MODE 3 computes footprints: camera_footprint.comp goes before the shader.
  if (!program)
    program = CompileProgram(kRenderFrameShader,
                             defines + static_cast<const char*>(kCameraFootprintShader));
  return program;
}

void GlRenderer::EnsureOutput(int width, int height) {
  if (output_ && output_width_ == width && output_height_ == height) return;
  if (width > limits_.max_texture_size || height > limits_.max_texture_size)
    throw Error(fmt::format("a {}x{} frame exceeds this GPU's largest texture ({} on {})", width,
                            height, limits_.max_texture_size, device().renderer));
  if (output_) glDeleteTextures(1, &output_);
  glGenTextures(1, &output_);
  glBindTexture(GL_TEXTURE_2D, output_);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, width, height);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  CheckGl(fmt::format("making a {}x{} frame", width, height));
  output_width_ = width;
  output_height_ = height;
}

double GlRenderer::RenderToTexture(const LightField& lf, const VirtualCamera& camera,
                                   const GlRenderOptions& options) {
  context_->MakeCurrent();
  if (options.workgroup_x < 1 || options.workgroup_y < 1 ||
      options.workgroup_x * options.workgroup_y > limits_.max_workgroup_invocations)
    throw UsageError(fmt::format("--workgroup {}x{}: this GPU runs 1 to {} invocations a group",
                                 options.workgroup_x, options.workgroup_y,
                                 limits_.max_workgroup_invocations));
  const LightFieldDims& d = lf.dims();
  if (d.rows < 1 || d.cols < 1 || d.n_s < 2 || d.n_t < 2)
    throw Error(
        fmt::format("the GL renderer needs at least 2x2 samples a view (this light field "
                    "has {}x{})",
                    d.n_s, d.n_t));
  if (options.integrator == Integrator::kCamerasQuadrilinear &&
      options.interpolation == Interpolation::kDepth)
    throw Error(
        "the depth lookup reads each lens sample's own scene point: it goes with the "
        "lens-samples integrator, not the cameras integrators");
  Upload(lf);
  EnsureOutput(camera.width(), camera.height());
  if (options.interpolation == Interpolation::kDepth) return RenderDepth(lf, camera, options);

  const bool lens_samples = options.integrator == Integrator::kLensSamples || camera.is_pinhole();
  // The cameras integrators read along the cameras' own lines (the focal-plane lookup); a
  // pinhole's limit under them is that lookup itself.
  const bool focal_plane = options.integrator != Integrator::kLensSamples ||
                           options.interpolation == Interpolation::kFocalPlane;
  const RaySetup setup(lf, camera, lens_samples);
  std::optional<CameraIntegratorFrame> cameras;
  int mode = lens_samples ? (focal_plane ? kLensFocalPlane : kLensQuadrilinear) : kCamerasUniform;
  std::vector<ShaderCameraWeight> weights;
  GLuint sampled = views_;  // the views the frame reads: as uploaded, or prefiltered
  double prefilter_ms = 0;
  float taper[2] = {0, 0};  // the quadrilinear limit's fade at the windows (render/window_taper.h)
  last_note_.clear();
  std::vector<CameraIntegratorFrame::Level> layout;  // the table's, built on the GPU
  double table_ms = 0;
  if (!lens_samples) {
    // The uniform case here; a table, when the footprints differ, on the GPU.
    cameras.emplace(lf, camera, /*tabulate=*/false);
    for (const GridCameraWeight& w : cameras->uniform_weights())
      weights.push_back({w.row * d.cols + w.col, float(w.weight)});
    if (cameras->needs_table()) {
      layout = BuildWeightTable(lf, camera, &table_ms);
      if (!layout.empty()) mode = kCamerasTable;
    }
    // The quadrilinear limit: the cameras integrator over views prefiltered by the hat scaled by
    // k (render/quadrilinear_limit.h), the filter a GPU pass, over the views some pixel reads
    // (every view when the weights come from the table).
    if (options.integrator == Integrator::kCamerasQuadrilinear) {
      const StPrefilter prefilter = QuadrilinearLimitPrefilter(lf, camera);
      if (prefilter.h_s >= 1e-3 || prefilter.h_t >= 1e-3) {
        std::vector<bool> read(d.view_count(), mode == kCamerasTable);
        for (const ShaderCameraWeight& w : weights) read[std::size_t(w.index)] = true;
        sampled = Prefilter(lf, prefilter, read, &prefilter_ms);
        // Every sample filtered, in the views' own layout: each view's window is its samples'.
        taper[0] = float(prefilter.h_s);
        taper[1] = float(prefilter.h_t);
        last_note_ = fmt::format(", views prefiltered ({:.2f} x {:.2f} samples)", prefilter.h_s,
                                 prefilter.h_t);
      }
    }
  }
  std::vector<OriginConstants> camera_st(std::size_t(d.view_count()));
  for (std::size_t i = 0; i < camera_st.size(); ++i) camera_st[i] = setup.camera_st(int(i));
  FillBuffer(buffers_[kLensUv], setup.lens_uv);
  FillBuffer(buffers_[kLensSt], setup.lens_st);
  FillBuffer(buffers_[kCameraSt], camera_st);
  FillBuffer(buffers_[kCameraWeights], weights);
  if (mode != kCamerasTable) FillBuffer(buffers_[kWeightTable], std::vector<float>{});
  std::vector<float> offsets;  // each view's window (k, l), read by the quadrilinear lookup
  for (std::size_t i = 0; i < setup.cam_k_offset.size(); ++i)
    offsets.insert(offsets.end(), {setup.cam_k_offset[i], setup.cam_l_offset[i]});
  FillBuffer(buffers_[kCameraOffsets], offsets);
  for (int b = 0; b < kBindings; ++b)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(b), buffers_[b]);
  CheckGl("uploading the frame's set-up");

  const GLuint program = Program(mode, setup.view_windows, options);
  glUseProgram(program);
  const Uniforms u{program};
  u.Int2("frame_size", camera.width(), camera.height());
  u.Int2("grid", d.cols, d.rows);
  u.Int2("st_size", d.n_s, d.n_t);
  glUniform4f(u.At("st_domain"), setup.domain[0], setup.domain[1], setup.domain[2],
              setup.domain[3]);
  u.Plane("uv", setup.uv);
  u.Plane("st", setup.st);
  u.Int("lens_count", int(setup.lens_uv.size()));
  u.Int("weight_count", int(weights.size()));
  glUniform2f(u.At("window_taper"), taper[0], taper[1]);
  u.Int("views", 0);
  if (mode == kCamerasTable) {
    FootprintUniforms(u, lf, camera);
    TableUniforms(u, layout);
  }
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, sampled);
  glBindImageTexture(0, output_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  CheckGl("setting the frame's parameters");

  last_lens_count_ = lens_samples ? static_cast<long long>(setup.lens_uv.size()) : 0;
  return prefilter_ms + table_ms + Dispatch(camera, options);
}

std::vector<CameraIntegratorFrame::Level> GlRenderer::BuildWeightTable(const LightField& lf,
                                                                       const VirtualCamera& camera,
                                                                       double* ms) {
  const auto start = std::chrono::steady_clock::now();
  const LightFieldDims& d = lf.dims();
  const auto program_for = [&](int pass) {
    const std::string defines =
        fmt::format("#define PASS {}\n{}", pass, static_cast<const char*>(kCameraFootprintShader));
    auto& program = programs_[fmt::format("weight table {}", pass)];
    if (!program) program = CompileProgram(kCameraWeightTableShader, defines);
    glUseProgram(program);
    return Uniforms{program};
  };
  // Pass 0: the range of the frame's footprints, read back.
  {
    const Uniforms u = program_for(0);
    u.Int2("frame_size", camera.width(), camera.height());
    u.Int2("grid", d.cols, d.rows);
    FootprintUniforms(u, lf, camera);
    const std::vector<std::int32_t> empty = {
        std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::min(),
        std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::min(),
        std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::min()};
    FillBuffer(range_buffer_, empty);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, range_buffer_);
    glDispatchCompute(GLuint((camera.width() + 15) / 16), GLuint((camera.height() + 7) / 8), 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  }
  std::int32_t ordered[6];
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, range_buffer_);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(ordered), ordered);
  CheckGl("finding the frame's footprints");
  double range[6];
  for (int i = 0; i < 6; ++i) {
    const std::int32_t bits = ordered[i] >= 0 ? ordered[i] : ordered[i] ^ 0x7fffffff;
    float value;
    std::memcpy(&value, &bits, sizeof(value));
    range[i] = value;
  }
  *ms = 0;
  if (ordered[0] > ordered[1]) return {};  // no pixel reaches the array
  std::vector<CameraIntegratorFrame::Level> layout = CameraIntegratorFrame::TableLayout(
      range[0], range[1], range[2], range[3], range[4], range[5]);
  const std::uint64_t cameras = std::uint64_t(d.view_count());
  const std::uint64_t nodes = std::uint64_t(layout[0].nx) * std::uint64_t(layout[0].ny);
  const std::uint64_t entries = std::uint64_t(layout.size()) * nodes * cameras;
  if (double(entries) * sizeof(float) > double(limits_.max_storage_block_bytes) ||
      entries > std::uint64_t(std::numeric_limits<std::uint32_t>::max()))
    throw Error(
        fmt::format("the cameras integrator's weight table for this frame ({}) exceeds this GPU's "
                    "storage block limit ({} on {}); a smaller frame or aperture fits",
                    Mib(double(entries) * sizeof(float)),
                    Mib(double(limits_.max_storage_block_bytes)), device().renderer));
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[kWeightTable]);
  glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(entries * sizeof(float)), nullptr,
               GL_DYNAMIC_COPY);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers_[kWeightTable]);
  // Passes 1 and 2: the entries, then each node's normalisation; as many groups of 64 as the
  // work needs, laid out in two dimensions (at most 65535 a dimension).
  const auto dispatch = [](std::uint64_t invocations) {
    const std::uint64_t groups = std::max<std::uint64_t>(1, (invocations + 63) / 64);
    const std::uint64_t x = std::min<std::uint64_t>(groups, 65535);
    glDispatchCompute(GLuint(x), GLuint((groups + x - 1) / x), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };
  for (const int pass : {1, 2}) {
    const Uniforms u = program_for(pass);
    u.Int2("grid", d.cols, d.rows);
    TableUniforms(u, layout);
    const std::uint64_t work = pass == 1 ? entries : std::uint64_t(layout.size()) * nodes;
    glUniform1ui(u.At("entries"), GLuint(work));
    dispatch(work);
  }
  CheckGl("building the cameras integrator's weight table");
  // The set-up's time as the frame's wall-clock sees it (it reads the range back).
  *ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return layout;
}

double GlRenderer::Dispatch(const VirtualCamera& camera, const GlRenderOptions& options) {
  return Timed("rendering the frame", [&] {
    glDispatchCompute(GLuint((camera.width() + options.workgroup_x - 1) / options.workgroup_x),
                      GLuint((camera.height() + options.workgroup_y - 1) / options.workgroup_y), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  });
}

double GlRenderer::Timed(const std::string& what, const std::function<void()>& passes) {
  const auto start = std::chrono::steady_clock::now();
  glBeginQuery(GL_TIME_ELAPSED, timer_);
  passes();
  glEndQuery(GL_TIME_ELAPSED);
  glFinish();
  const double wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  CheckGl(what);
  GLuint64 nanoseconds = 0;
  glGetQueryObjectui64v(timer_, GL_QUERY_RESULT, &nanoseconds);
  // A software GL (llvmpipe) runs compute work outside its timer queries (they read 0): there
  // the passes' wall-clock time, from the first dispatch to glFinish, stands in.
  const double gpu_ms = double(nanoseconds) * 1e-6;
  return device().software || gpu_ms <= 0 ? wall_ms : gpu_ms;
}

void GlRenderer::UploadDepth(const DepthSet& depth) {
  const LightFieldDims& d = depth.dims();
  if (depth_maps_ && uploaded_depth_ == &depth && depth_dims_ == d) return;
  const double bytes = 4.0 * double(d.samples_per_view()) * double(d.view_count());
  RequireGpuMemory(bytes, "the depth maps");
  if (depth_maps_) glDeleteTextures(1, &depth_maps_);
  depth_maps_ = 0;
  uploaded_depth_ = nullptr;
  depth_maps_ = NewTextureArray(GL_R32F, d, GL_NEAREST, bytes, "the depth maps");
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) {
      if (!depth.has(r, c)) continue;  // never read: the shader knows which views have maps
      const cv::Mat& m = depth.at(r, c).depth;
      glPixelStorei(GL_UNPACK_ROW_LENGTH, GLint(m.step1()));
      glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, r * d.cols + c, d.n_s, d.n_t, 1, GL_RED,
                      GL_FLOAT, m.ptr<float>(0));
    }
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  CheckGl("uploading the depth maps");
  uploaded_depth_ = &depth;
  depth_dims_ = d;
}

double GlRenderer::RenderDepth(const LightField& lf, const VirtualCamera& camera,
                               const GlRenderOptions& options) {
  if (options.integrator != Integrator::kLensSamples)
    throw Error(
        "the depth lookup reads each lens sample's own scene point: it goes with the "
        "lens-samples integrator, not the cameras integrator");
  if (!options.depth) throw Error("the depth lookup needs the views' depth maps");
  const LightFieldSampler sampler(lf);
  // The CPU's sampler checks the maps against the light field and gives the march's constants.
  const DepthAwareSampler reference(lf, *options.depth, sampler);
  UploadDepth(*options.depth);
  const LightFieldDims& d = lf.dims();
  const LookupPlanes planes = LookupPlanesOf(lf);
  const Vec3& origin = planes.p_ca;  // positions go to the shader relative to p_ca
  std::vector<float> lens;           // vec4 each
  if (!camera.is_pinhole())
    for (const Vec2& disk : camera.lens_samples()) {
      const Vec3 x = camera.lens_point(disk) - origin;
      lens.insert(lens.end(), {float(x.x()), float(x.y()), float(x.z()), 0.0f});
    }
  std::vector<float> centres, offsets;
  std::vector<std::int32_t> has;
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) {
      const Vec3 x = lf.camera_center(r, c) - origin;
      centres.insert(centres.end(), {float(x.x()), float(x.y()), float(x.z()), 0.0f});
      const StOffset o = lf.st_offset(r, c);
      offsets.insert(offsets.end(), {float(o.k), float(o.l)});
      has.push_back(reference.reads(r, c) ? 1 : 0);
    }
  FillBuffer(buffers_[0], lens);
  FillBuffer(buffers_[1], centres);
  FillBuffer(buffers_[2], offsets);
  FillBuffer(buffers_[3], has);
  for (int b = 0; b < 4; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(b), buffers_[b]);
  CheckGl("uploading the frame's set-up");

  const bool view_windows = !lf.st_offsets().empty();
  const std::string defines =
      fmt::format("#define WORKGROUP_X {}\n#define WORKGROUP_Y {}\n#define VIEW_WINDOWS {}\n",
                  options.workgroup_x, options.workgroup_y, view_windows ? 1 : 0);
  auto& program = programs_["depth|" + defines];
  if (!program) program = CompileProgram(kRenderDepthShader, defines);
  glUseProgram(program);
  const Uniforms u{program};
  u.Int2("frame_size", camera.width(), camera.height());
  u.Int2("grid", d.cols, d.rows);
  u.Int2("st_size", d.n_s, d.n_t);
  u.Vec3f("n_ca", planes.n_ca);
  u.Vec3f("u_scaled", planes.u_scaled);
  u.Vec3f("v_scaled", planes.v_scaled);
  u.Vec3f("st_origin", planes.st_origin - origin);
  u.Vec3f("n_st", planes.n_st);
  u.Vec3f("s_scaled", planes.s_scaled);
  u.Vec3f("t_scaled", planes.t_scaled);
  glUniform4f(u.At("grid_st"), float(planes.s0), float(planes.t0), float(planes.s_to_k),
              float(planes.t_to_l));
  glUniform4f(u.At("domain"), float(planes.u_s0), float(planes.u_t0), float(planes.u_s1),
              float(planes.u_t1));
  u.Vec3f("eye", camera.e_c() - origin);
  u.Vec3f("cam_u", camera.u_c());
  u.Vec3f("cam_v", camera.v_c());
  u.Vec3f("cam_n", camera.n_c());
  // direction_through's half-angles: how far the film's right and top edges lie along u_c and
  // v_c from its centre's direction.
  const Vec3 centre = camera.direction_through(0.5 * camera.width(), 0.5 * camera.height());
  const Vec3 right = camera.direction_through(camera.width(), 0.5 * camera.height()) - centre;
  const Vec3 top = camera.direction_through(0.5 * camera.width(), camera.height()) - centre;
  glUniform2f(u.At("tan_half"), float(right.dot(camera.u_c())), float(top.dot(camera.v_c())));
  glUniform2f(u.At("principal_offset"), float(camera.params().principal_offset_px.x()),
              float(camera.params().principal_offset_px.y()));
  u.Float("focus_distance", camera.params().focus_distance_mm);
  u.Int("lens_count", int(lens.size() / 4));
  u.Int("antialias", options.antialias ? 1 : 0);
  u.Int("agreeing_blend", options.depth_blend == DepthBlend::kAgreeing ? 1 : 0);
  // render_depth.comp's BlendAgreeing holds the cameras within reach in arrays of 5 x 5.
  static_assert(kAgreeingReach <= 2.0, "render_depth.comp's block would overflow");
  u.Float("agreeing_reach", float(kAgreeingReach));
  u.Float("agreement_floor", float(kAgreementFloor));
  u.Int("cubic_reads", DepthLookupReadsCubic(camera, sampler) ? 1 : 0);
  u.Int("encoded_reads", views_encoded_ ? 1 : 0);
  u.Float("q_near", reference.q_near());
  u.Float("q_far", reference.q_far());
  u.Float("unit_q", reference.unit_q());
  u.Int("views", 0);
  u.Int("depth_maps", 1);
  u.Int("views_encoded", 2);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D_ARRAY, views_encoded_ ? views_encoded_ : views_);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, depth_maps_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, views_);
  glBindImageTexture(0, output_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  CheckGl("setting the frame's parameters");
  // The rays a pixel casts, as the CPU counts them (its lens samples; a pinhole's one, or its
  // 2 x 2 film points when antialiased).
  last_lens_count_ = options.antialias && camera.is_pinhole()
                         ? 4
                         : static_cast<long long>(camera.lens_samples().size());
  last_note_ = " (depth lookup)";
  return Dispatch(camera, options);
}

unsigned GlRenderer::Prefilter(const LightField& lf, const StPrefilter& prefilter,
                               const std::vector<bool>& read, double* ms) {
  const LightFieldDims& d = lf.dims();
  const std::vector<float> taps_s = PrefilterTaps(prefilter.h_s);
  const std::vector<float> taps_t = PrefilterTaps(prefilter.h_t);
  std::vector<std::int32_t> layers;
  for (std::size_t v = 0; v < read.size(); ++v)
    if (read[v]) layers.push_back(std::int32_t(v));
  // The same filter over the same views of the same light field: still in place.
  const std::string key = fmt::format("{}|{}|{}|{}", uploaded_serial_, fmt::join(taps_s, ","),
                                      fmt::join(taps_t, ","), fmt::join(layers, ","));
  if (key == filtered_key_) return filtered_[1];
  filtered_key_.clear();
  if (!(filtered_dims_ == d) || !filtered_[0]) {
    // Two RGBA16F arrays as large as the light field: the first pass's output and the second's.
    const double bytes = 8.0 * double(d.samples_per_view()) * double(d.view_count());
    const std::string what = "the quadrilinear limit's prefiltered views";
    RequireGpuMemory(2 * bytes, what);
    glDeleteTextures(2, filtered_);
    filtered_[0] = filtered_[1] = 0;
    for (GLuint& texture : filtered_)
      texture = NewTextureArray(GL_RGBA16F, d, GL_LINEAR, bytes, what);
    filtered_dims_ = d;
  }
  auto& program = programs_["prefilter"];
  if (!program) program = CompileProgram(kPrefilterViewsShader, "");
  glUseProgram(program);
  const Uniforms u{program};
  u.Int2("size", d.n_s, d.n_t);
  u.Int("source", 0);
  FillBuffer(prefilter_buffers_[1], layers);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, prefilter_buffers_[1]);
  const std::pair<GLuint, GLuint> passes[2] = {{views_, filtered_[0]},
                                               {filtered_[0], filtered_[1]}};
  *ms = Timed("prefiltering the views", [&] {
    for (int pass = 0; pass < 2; ++pass) {
      const std::vector<float>& taps = pass == 0 ? taps_s : taps_t;
      FillBuffer(prefilter_buffers_[0], taps);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, prefilter_buffers_[0]);
      u.Int2("axis", pass == 0 ? 1 : 0, pass == 0 ? 0 : 1);
      u.Int("tap_count", int(taps.size()));
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_2D_ARRAY, passes[pass].first);
      glBindImageTexture(0, passes[pass].second, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
      glDispatchCompute(GLuint((d.n_s + 15) / 16), GLuint((d.n_t + 15) / 16),
                        GLuint(layers.size()));
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
  });
  filtered_key_ = key;
  return filtered_[1];
}

RenderResult GlRenderer::Render(const LightField& lf, const VirtualCamera& camera,
                                const GlRenderOptions& options) {
  RenderResult result;
  result.gpu_ms = RenderToTexture(lf, camera, options);
  const int width = camera.width(), height = camera.height();
  std::vector<float> pixels(std::size_t(width) * std::size_t(height) * 4);
  glBindTexture(GL_TEXTURE_2D, output_);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, pixels.data());
  CheckGl("reading the frame back");
  result.image = cv::Mat(height, width, CV_32FC3);
  result.hit_mask = cv::Mat(height, width, CV_8UC1);
  result.counts = cv::Mat(height, width, CV_32SC1);
  for (int j = 0; j < height; ++j) {
    const float* in = pixels.data() + std::size_t(j) * std::size_t(width) * 4;
    auto* out = result.image.ptr<cv::Vec3f>(camera.image_row(j));
    auto* mask = result.hit_mask.ptr<std::uint8_t>(camera.image_row(j));
    auto* counts = result.counts.ptr<std::int32_t>(camera.image_row(j));
    for (int i = 0; i < width; ++i) {
      out[i] = {in[4 * i], in[4 * i + 1], in[4 * i + 2]};
      const auto count = static_cast<long long>(in[4 * i + 3]);
      mask[i] = count > 0 ? 255 : 0;
      counts[i] = static_cast<std::int32_t>(count);
      result.rays_hit += count;
    }
  }
  result.rays = last_lens_count_ > 0 ? static_cast<long long>(width) * height * last_lens_count_
                                     : result.rays_hit;
  result.path = "gl (" + device().renderer + ")" + last_note_;
  return result;
}

}  // namespace lfcam
