#pragma once
// What the viewer renders next, so that it never blocks: a frame whose full-resolution render
// costs more than the frame budget is rendered at a reduced scale while the view is moving and
// at full resolution once it rests; with the lens-samples integrator the full-resolution frame
// then comes in parts, a range of lens samples each, accumulated (LensSampleAccumulator) so
// that the picture refines to exactly what `lfcam render` writes. CPU frames render on a worker
// thread (the window keeps drawing the last frame); GL frames render in the window's context,
// into the renderer's output texture, and are drawn from there without a read-back (the parts
// of an accumulated frame are read back and added on the CPU).
#include <chrono>
#include <future>
#include <memory>
#include <optional>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/frame_renderer.h"
#include "lfcam/render/lens_sample_accumulator.h"
#include "lfcam/render/view_file.h"

namespace lfcam {

bool SameView(const ViewSettings& a, const ViewSettings& b);

// The camera of `view` at `scale` of its resolution (at least 16 pixels a side, same aspect).
VirtualCameraParams ScaledCamera(const VirtualCameraParams& camera, double scale);

class FrameScheduler {
 public:
  // `lf` is the light field rendered (shared: a render in flight keeps the frame it started on
  // alive while a video moves on).
  FrameScheduler(std::shared_ptr<const LightField> lf, const FrameRenderer& renderer,
                 FrameRenderOptions options, double budget_ms);
  ~FrameScheduler();
  FrameScheduler(const FrameScheduler&) = delete;
  FrameScheduler& operator=(const FrameScheduler&) = delete;

  // A light field video's frame `index` to render from now on (the view is then not the
  // frame shown, whatever the camera).
  void SetLightField(std::shared_ptr<const LightField> lf, std::int64_t index);
  // The frame budget (ms): frames costlier than this render reduced while moving.
  void set_budget_ms(double budget_ms) { budget_ms_ = budget_ms; }

  // Called once a loop with the view wanted (at full resolution) and whether it is moving.
  // Returns true when a new frame is ready to draw.
  bool Update(const ViewSettings& wanted, bool moving);
  // The frame shown is `wanted` at full resolution, of the current light field frame, and
  // nothing is rendering.
  bool converged(const ViewSettings& wanted) const;
  // The light field video frame the shown picture was rendered from.
  std::int64_t shown_index() const { return shown_index_; }

  // The frame to draw: the GL renderer's output texture, or else a CPU image (linear, top-down).
  bool on_gl() const { return shown_on_gl_; }
  // Of an accumulated frame: the parts shown so far and all of them (1 and 1 otherwise).
  int parts_shown() const { return parts_shown_; }
  int parts() const { return parts_; }
  const RenderResult& shown() const { return shown_; }
  const std::optional<ViewSettings>& shown_view() const { return shown_view_; }
  double shown_scale() const { return shown_scale_; }
  double shown_ms() const { return shown_ms_; }         // its render's wall-clock time
  double full_estimate_ms() const { return full_ms_; }  // the last full-resolution render's

  // A full-resolution render of `view`, now, read back (for screenshots).
  RenderResult RenderNow(const ViewSettings& view) const;

 private:
  struct Job {
    ViewSettings view;
    std::shared_ptr<const LightField> lf;
    std::int64_t index = 0;
    double scale = 1;
    int part = 0, parts = 1;  // lens samples [n_ls * part / parts, n_ls * (part + 1) / parts)
    std::chrono::steady_clock::time_point start;
  };
  void Start(const Job& job);
  FrameRenderOptions OptionsFor(const ViewSettings& view) const;
  void Finish(const Job& job, RenderResult result);

  bool Same(const ViewSettings& wanted) const;

  std::shared_ptr<const LightField> lf_;
  std::int64_t index_ = 0, shown_index_ = -1;
  const FrameRenderer& renderer_;
  FrameRenderOptions options_;
  double budget_ms_;
  RenderResult shown_;
  std::optional<ViewSettings> shown_view_;
  double shown_scale_ = 0, shown_ms_ = 0, full_ms_ = 0;
  bool shown_on_gl_ = false;
  int parts_shown_ = 1, parts_ = 1;
  double parts_ms_ = 0;  // the accumulated frame's parts so far
  LensSampleAccumulator accumulator_;
  std::optional<Job> job_;
  std::future<RenderResult> pending_;  // the CPU's worker
};

}  // namespace lfcam
