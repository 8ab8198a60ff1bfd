#include "lfcam/depth/gl_cost_volume.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "lfcam/core/error.h"
#include "lfcam/depth/shaders/sweep_costs.comp.h"
#include "lfcam/depth/shaders/sweep_window.comp.h"
#include "lfcam/gpu/gl_program.h"

namespace lfcam {
namespace {

constexpr int kGroupX = 16, kGroupY = 8;  // the shaders' local size

// ShiftedSweep::Read as the shader reads it (std430).
struct ShaderRead {
  std::int32_t x0, y0, sub_arrays, scaled;
  float wx[4], wy[4];
  std::int32_t x_lo, x_hi, y_lo, y_hi;
  float scale[4];  // ax, bx, ay, by
};
static_assert(sizeof(ShaderRead) == 80, "std430 layout of Read");

GLuint NewTexture(GLenum target) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(target, texture);
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

}  // namespace

std::unique_ptr<GlCostVolume> GlCostVolume::Create(bool prefer_hardware) {
  auto engine = std::unique_ptr<GlCostVolume>(new GlCostVolume());
  std::promise<void> started;
  std::future<void> ready = started.get_future();
  engine->thread_ = std::thread(&GlCostVolume::GlThread, engine.get(), prefer_hardware, &started);
  try {
    ready.get();  // the context made, or why not
  } catch (...) {
    engine->thread_.join();  // it has ended
    engine->thread_ = std::thread();
    throw;
  }
  return engine;
}

void GlCostVolume::GlThread(bool prefer_hardware, std::promise<void>* started) {
  try {
    context_ = GlContext::Create(prefer_hardware);
    device_ = context_->device();
    GLint size = 0, layers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &size);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &layers);
    max_texture_size_ = size;
    max_layers_ = layers;
  } catch (...) {
    started->set_exception(std::current_exception());
    return;
  }
  started->set_value();
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || work_ != nullptr; });
    if (work_ != nullptr) {
      const std::function<void()>* work = work_;
      lock.unlock();
      std::exception_ptr failure;
      try {
        (*work)();
      } catch (...) {
        failure = std::current_exception();
      }
      lock.lock();
      failure_ = failure;
      work_ = nullptr;
      done_.notify_all();
      continue;
    }
    break;  // stopping, no work left
  }
  lock.unlock();
  DeleteObjects();
  if (costs_program_) glDeleteProgram(costs_program_);
  if (window_program_) glDeleteProgram(window_program_);
  context_.reset();
}

GlCostVolume::~GlCostVolume() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void GlCostVolume::OnGlThread(const std::function<void()>& work) {
  std::lock_guard one(submit_);
  std::unique_lock lock(mutex_);
  work_ = &work;
  failure_ = nullptr;
  wake_.notify_all();
  done_.wait(lock, [&] { return work_ == nullptr; });
  if (failure_) std::rethrow_exception(failure_);
}

void GlCostVolume::RanOnCpu(const std::string& why) {
  std::lock_guard lock(mutex_);
  ++tally_.cpu_sweeps;
  if (std::find(tally_.cpu_reasons.begin(), tally_.cpu_reasons.end(), why) ==
      tally_.cpu_reasons.end())
    tally_.cpu_reasons.push_back(why);
}

GlCostVolume::Tally GlCostVolume::tally() const {
  std::lock_guard lock(mutex_);
  return tally_;
}
CostVolume GlCostVolume::SweepOnGlThread(const ShiftedSweep& sweep) {
  const int w = sweep.width, h = sweep.height, n = sweep.labels;
  const int views = int(sweep.views.size());
  const auto start = std::chrono::steady_clock::now();
  if (const std::string why = Refuses(sweep); !why.empty()) throw Error(why);
  if (costs_program_ == 0) costs_program_ = CompileProgram(kSweepCostsShader, "");
  if (window_program_ == 0) window_program_ = CompileProgram(kSweepWindowShader, "");

  const std::size_t plane = std::size_t(w) * h;
  MakeRoom(w, h, views, n);
  const GLuint* t = textures_;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  // The views: channels 0 .. 3 interleaved, channel 4 alone.
  std::vector<std::int16_t> rgbx(plane * 4);
  for (int v = 0; v < views; ++v) {
    const std::int16_t* packed = sweep.views[std::size_t(v)];
    tbb::this_task_arena::isolate([&] {
      tbb::parallel_for(std::size_t(0), plane, [&](std::size_t p) {
        for (int c = 0; c < 4; ++c)
          rgbx[4 * p + std::size_t(c)] = packed[std::size_t(c) * plane + p];
      });
    });
    glBindTexture(GL_TEXTURE_2D_ARRAY, t[0]);
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, v, w, h, 1, GL_RGBA_INTEGER, GL_SHORT,
                    rgbx.data());
    glBindTexture(GL_TEXTURE_2D_ARRAY, t[1]);
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, v, w, h, 1, GL_RED_INTEGER, GL_SHORT,
                    packed + 4 * plane);
  }
  {
    std::vector<float> reference(plane * 4);
    for (std::size_t p = 0; p < plane; ++p)
      for (int c = 0; c < 4; ++c)
        reference[4 * p + std::size_t(c)] = sweep.reference[std::size_t(c) * plane + p];
    glBindTexture(GL_TEXTURE_2D, t[2]);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, reference.data());
    glBindTexture(GL_TEXTURE_2D, t[3]);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RED, GL_FLOAT, sweep.reference + 4 * plane);
  }
  CheckGl(fmt::format("uploading {} views of {}x{}", views, w, h));
  {
    std::vector<ShaderRead> reads(sweep.reads.size());
    for (std::size_t i = 0; i < reads.size(); ++i) {
      const ShiftedSweep::Read& r = sweep.reads[i];
      ShaderRead& s = reads[i];
      s = {r.x0,
           r.y0,
           std::int32_t(sweep.sub_arrays[i % std::size_t(views)]),
           r.scaled,
           {},
           {},
           r.x_lo,
           r.x_hi,
           r.y_lo,
           r.y_hi,
           {float(r.ax), float(r.bx), float(r.ay), float(r.by)}};
      std::copy(r.wx.begin(), r.wx.end(), s.wx);
      std::copy(r.wy.begin(), r.wy.end(), s.wy);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, reads_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(reads.size() * sizeof(ShaderRead)),
                 reads.data(), GL_STATIC_DRAW);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, reads_);
  }
  CheckGl("uploading the views' shifts");
  glFinish();
  const auto uploaded = std::chrono::steady_clock::now();

  const GLuint groups_x = GLuint((w + kGroupX - 1) / kGroupX);
  const GLuint groups_y = GLuint((h + kGroupY - 1) / kGroupY);
  glUseProgram(costs_program_);
  glUniform1i(glGetUniformLocation(costs_program_, "view_count"), views);
  glUniform2i(glGetUniformLocation(costs_program_, "size"), w, h);
  glUniform4f(glGetUniformLocation(costs_program_, "unit_rgbx"), 1.0f / sweep.packed_unit[0],
              1.0f / sweep.packed_unit[1], 1.0f / sweep.packed_unit[2],
              1.0f / sweep.packed_unit[3]);
  glUniform1f(glGetUniformLocation(costs_program_, "unit_y"), 1.0f / sweep.packed_unit[4]);
  glUniform4f(glGetUniformLocation(costs_program_, "terms"), sweep.color_cap, sweep.gradient_cap,
              sweep.color_weight, sweep.gradient_weight);
  glUniform1i(glGetUniformLocation(costs_program_, "sub_arrays"), sweep.sub_array_count);
  glUniform1f(glGetUniformLocation(costs_program_, "read_sigma"), float(sweep.read_sigma));
  glUseProgram(window_program_);
  glUniform2i(glGetUniformLocation(window_program_, "size"), w, h);
  glUniform1i(glGetUniformLocation(window_program_, "radius"), std::max(0, sweep.window_radius));
  glUniform1f(glGetUniformLocation(window_program_, "min_count"), sweep.min_count);
  // (infinity as the largest float: never exceeded, and finite in any GLSL implementation)
  glUniform1f(glGetUniformLocation(window_program_, "pair_min_count"),
              std::min(sweep.pair_min_count, std::numeric_limits<float>::max()));
  glUniform1f(glGetUniformLocation(window_program_, "unit"), float(CostVolume::kCostUnit));
  glUniform1ui(glGetUniformLocation(window_program_, "most"), sweep.most);
  glUniform1i(glGetUniformLocation(window_program_, "sub_arrays"), sweep.sub_array_count);
  glUniform1f(glGetUniformLocation(window_program_, "quarter_weight"), sweep.quarter_weight);
  static_assert(ShiftedSweep::kChannels == 5, "four channels interleaved and one alone");
  for (int i = 0; i < n; ++i) {
    glUseProgram(costs_program_);
    glUniform1i(glGetUniformLocation(costs_program_, "plane"), i);
    for (int unit = 0; unit < 4; ++unit) {
      glActiveTexture(GLenum(GL_TEXTURE0 + unit));
      glBindTexture(unit < 2 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D, t[unit]);
    }
    glBindImageTexture(0, t[4], 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groups_x, groups_y, 1);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    glUseProgram(window_program_);
    glUniform1i(glGetUniformLocation(window_program_, "plane"), i);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t[4]);
    glBindImageTexture(1, t[5], 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R16UI);
    glDispatchCompute(groups_x, groups_y, 1);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
  }
  CheckGl(fmt::format("sweeping {} planes", n));
  glFinish();
  const auto swept = std::chrono::steady_clock::now();

  // Read back through a pixel buffer: the GPU copies the volume into it at its own speed (read
  // into the program's memory directly, glGetTexImage converts on the CPU at about a gigabyte a
  // second), already laid out label-fastest, then into the volume.
  CostVolume volume;
  volume.width = w;
  volume.height = h;
  volume.labels = n;
  volume.cost.resize(plane * std::size_t(n));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_);
  glBindTexture(GL_TEXTURE_2D_ARRAY, t[5]);
  glGetTexImage(GL_TEXTURE_2D_ARRAY, 0, GL_RED_INTEGER, GL_UNSIGNED_SHORT, nullptr);
  glGetBufferSubData(GL_PIXEL_PACK_BUFFER, 0,
                     GLsizeiptr(volume.cost.size() * sizeof(std::uint16_t)), volume.cost.data());
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  CheckGl("reading the cost volume back");
  {
    const auto end = std::chrono::steady_clock::now();
    const auto seconds = [](auto a, auto b) {
      return std::chrono::duration<double>(b - a).count();
    };
    std::lock_guard lock(mutex_);
    ++tally_.gpu_sweeps;
    tally_.gpu_seconds += seconds(start, end);
    tally_.upload_seconds += seconds(start, uploaded);
    tally_.pass_seconds += seconds(uploaded, swept);
    tally_.readback_seconds += seconds(swept, end);
  }
  return volume;
}

void GlCostVolume::MakeRoom(int w, int h, int views, int n) {
  if (w == made_width_ && h == made_height_ && n == made_labels_ && views <= made_views_) return;
  DeleteObjects();
  GLuint* t = textures_;
  t[0] = NewTexture(GL_TEXTURE_2D_ARRAY);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA16I, w, h, views);
  t[1] = NewTexture(GL_TEXTURE_2D_ARRAY);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_R16I, w, h, views);
  t[2] = NewTexture(GL_TEXTURE_2D);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, w, h);
  t[3] = NewTexture(GL_TEXTURE_2D);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_R32F, w, h);
  t[4] = NewTexture(GL_TEXTURE_2D_ARRAY);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA32F, w, h, 8);  // sweep_costs.comp's layers
  t[5] = NewTexture(GL_TEXTURE_2D_ARRAY);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_R16UI, n, w, h);  // label-fastest: (plane, x), y
  glGenBuffers(1, &reads_);
  glGenBuffers(1, &pack_);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_);
  glBufferData(GL_PIXEL_PACK_BUFFER,
               GLsizeiptr(std::size_t(w) * std::size_t(h) * std::size_t(n) * sizeof(std::uint16_t)),
               nullptr, GL_STREAM_READ);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  try {
    CheckGl(
        fmt::format("making room on the GPU for {} views and {} planes of {}x{}", views, n, w, h));
  } catch (...) {
    DeleteObjects();  // so that the next sweep makes room afresh
    throw;
  }
  made_width_ = w;
  made_height_ = h;
  made_views_ = views;
  made_labels_ = n;
}

void GlCostVolume::DeleteObjects() {
  glDeleteTextures(6, textures_);
  std::fill(std::begin(textures_), std::end(textures_), 0u);
  if (reads_) glDeleteBuffers(1, &reads_);
  if (pack_) glDeleteBuffers(1, &pack_);
  reads_ = pack_ = 0;
  made_width_ = made_height_ = made_views_ = made_labels_ = 0;
}

std::string GlCostVolume::Refuses(const ShiftedSweep& sweep) const {
  const int w = sweep.width, h = sweep.height, n = sweep.labels;
  const int views = int(sweep.views.size());
  // The views: w x h, a layer each; the volume: (plane, x) texels, a layer per row.
  if (w > max_texture_size_ || h > max_texture_size_ || n > max_texture_size_ ||
      views > max_layers_ || h > max_layers_)
    return fmt::format(
        "the GPU ({}) takes textures of at most {} texels a side and {} layers; this sweep "
        "needs {}x{} samples, {} views and {} planes ({} rows as layers)",
        device_.renderer, max_texture_size_, max_layers_, w, h, views, n, h);
  return {};
}

CostVolume GlCostVolume::Sweep(const ShiftedSweep& sweep) {
  const int w = sweep.width, h = sweep.height, n = sweep.labels;
  const int views = int(sweep.views.size());
  if (w <= 0 || h <= 0 || n <= 0 || views <= 0 ||
      sweep.reads.size() != std::size_t(n) * std::size_t(views) ||
      sweep.sub_arrays.size() != std::size_t(views) ||
      (sweep.sub_array_count != ShiftedSweep::kHalves &&
       sweep.sub_array_count != ShiftedSweep::kSubArrays))
    throw Error("the GPU sweep was given an inconsistent sweep");
  CostVolume volume;
  const std::function<void()> work = [&] { volume = SweepOnGlThread(sweep); };
  OnGlThread(work);
  return volume;
}

}  // namespace lfcam
