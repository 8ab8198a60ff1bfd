#pragma once
// The plane sweep's cost volumes on a GPU (docs/depth.md, "On a GPU"): OpenGL 4.3 compute
// shaders, headless through EGL (gpu/gl_context.h), computing the same volume as the CPU's
// SweepViews::Sweep (depth/cost_volume.h) for sweeps whose views are all read shifted (the
// st-plane parallel to the array's plane: rectified, parallel and built light fields). The
// semi-global matching and the steps after it stay on the CPU (depth/plane_sweep.h).
//
// One engine serves every thread: its GL context lives on a thread of its own, which runs the
// sweeps one at a time (EstimateDepthSet estimates several views at once; their sweeps queue,
// the rest of each estimate runs beside). GL is only ever called on that thread.
#include <condition_variable>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "lfcam/depth/cost_volume.h"
#include "lfcam/gpu/gl_context.h"

namespace lfcam {

class GlCostVolume final : public CostVolumeEngine {
 public:
  // Throws lfcam::Error naming what is missing when no GL 4.3 context can be made. With
  // `prefer_hardware` false, Mesa's software rasteriser is taken first when there is one.
  static std::unique_ptr<GlCostVolume> Create(bool prefer_hardware = true);
  ~GlCostVolume() override;
  GlCostVolume(const GlCostVolume&) = delete;
  GlCostVolume& operator=(const GlCostVolume&) = delete;

  // Throws lfcam::Error when GL fails (out of GPU memory: it says so).
  CostVolume Sweep(const ShiftedSweep& sweep) override;
  std::string Refuses(const ShiftedSweep& sweep) const override;
  void RanOnCpu(const std::string& why) override;

  const GlDeviceInfo& device() const { return device_; }
  // What ran where so far: volumes swept here, the seconds they took (upload, the passes and
  // reading back), and why any ran on the CPU instead (each reason once).
  struct Tally {
    int gpu_sweeps = 0;
    double gpu_seconds = 0;
    // Of gpu_seconds: uploading the views (and making room when a sweep's size is new), the
    // passes, and reading the volume back.
    double upload_seconds = 0, pass_seconds = 0, readback_seconds = 0;
    int cpu_sweeps = 0;
    std::vector<std::string> cpu_reasons;
  };
  Tally tally() const;

 private:
  GlCostVolume() = default;
  // Runs `work` on the GL thread and waits for it; rethrows what it threw.
  void OnGlThread(const std::function<void()>& work);
  void GlThread(bool prefer_hardware, std::promise<void>* started);
  // The sweep, on the GL thread.
  CostVolume SweepOnGlThread(const ShiftedSweep& sweep);
  // Makes room for a sweep of this size, keeping what the last sweep made where it fits (the
  // sweeps of one light field's views are all of one size).
  void MakeRoom(int width, int height, int views, int labels);
  void DeleteObjects();

  std::thread thread_;
  std::unique_ptr<GlContext> context_;  // made, used and destroyed on thread_
  GlDeviceInfo device_;
  std::mutex submit_;         // one caller at a time
  mutable std::mutex mutex_;  // the hand-over below, and the tally
  std::condition_variable wake_, done_;
  const std::function<void()>* work_ = nullptr;
  std::exception_ptr failure_;
  bool stop_ = false;
  unsigned costs_program_ = 0, window_program_ = 0;
  int max_texture_size_ = 0, max_layers_ = 0;  // the GPU's limits, read when the context is made
  // views_rgbx, views_y, reference_rgbx, reference_y, sums, volume; the reads' buffer and the
  // volume's read-back buffer; the size they were made for.
  unsigned textures_[6] = {}, reads_ = 0, pack_ = 0;
  int made_width_ = 0, made_height_ = 0, made_views_ = 0, made_labels_ = 0;
  Tally tally_;
};

}  // namespace lfcam
