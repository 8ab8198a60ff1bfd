#include "lfcam/viewer/frame_scheduler.h"

#include <algorithm>
#include <cmath>

namespace lfcam {

bool SameView(const ViewSettings& a, const ViewSettings& b) {
  const VirtualCameraParams &p = a.camera, &q = b.camera;
  return p.width == q.width && p.height == q.height && p.eye == q.eye && p.look_at == q.look_at &&
         p.up == q.up && p.focal_length_mm == q.focal_length_mm &&
         p.focus_distance_mm == q.focus_distance_mm && p.aperture_mm == q.aperture_mm &&
         p.lens_rate == q.lens_rate && p.breathing == q.breathing && a.integrator == b.integrator &&
         a.interpolation == b.interpolation;
}

VirtualCameraParams ScaledCamera(const VirtualCameraParams& camera, double scale) {
  VirtualCameraParams p = camera;
  if (scale >= 1) return p;
  p.width = std::max(16, int(std::lround(camera.width * scale)));
  p.height = std::max(16, int(std::lround(double(p.width) * camera.height / camera.width)));
  return p;
}

FrameScheduler::FrameScheduler(const LightField& lf, const FrameRenderer& renderer,
                               FrameRenderOptions options, double budget_ms)
    : lf_(lf), renderer_(renderer), options_(std::move(options)), budget_ms_(budget_ms) {}

FrameScheduler::~FrameScheduler() {
  if (pending_.valid()) pending_.wait();
}

FrameRenderOptions FrameScheduler::OptionsFor(const ViewSettings& view) const {
  FrameRenderOptions o = options_;
  o.integrator = view.integrator;
  o.interpolation = view.interpolation;
  return o;
}

RenderResult FrameScheduler::RenderNow(const ViewSettings& view) const {
  return renderer_.Render(lf_, VirtualCamera(view.camera), OptionsFor(view));
}

void FrameScheduler::Finish(const Job& job, RenderResult result) {
  shown_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - job.start)
          .count();
  if (job.scale >= 1) full_ms_ = shown_ms_;
  shown_ = std::move(result);
  shown_view_ = job.view;
  shown_scale_ = job.scale;
}

bool FrameScheduler::Update(const ViewSettings& wanted, bool moving) {
  bool ready = false;
  if (pending_.valid() && pending_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    Finish(*job_, pending_.get());
    job_.reset();
    ready = true;
  }
  if (pending_.valid()) return ready;  // the worker is busy; the newest view comes next
  const bool same = shown_view_ && SameView(*shown_view_, wanted);
  if (same && shown_scale_ >= 1) return ready;
  // Reduced while moving when a full frame would cost more than the budget (or was not measured).
  double scale = 1;
  if (moving && full_ms_ > budget_ms_)
    scale = std::clamp(std::sqrt(budget_ms_ / full_ms_), 0.125, 1.0);
  if (same && scale <= shown_scale_) return ready;  // nothing better to show yet
  Job job{wanted, scale, std::chrono::steady_clock::now()};
  const VirtualCamera camera(ScaledCamera(wanted.camera, scale));
  if (renderer_.uses_gl()) {
    // In the window's context: the frame lands in the renderer's output texture.
    RenderResult result;
    result.gpu_ms = renderer_.gl()->RenderToTexture(
        lf_, camera,
        {wanted.integrator, wanted.interpolation, options_.workgroup_x, options_.workgroup_y});
    result.path = "gl (" + renderer_.gl()->device().renderer + ")";
    Finish(job, std::move(result));
    return true;
  }
  job_ = job;
  const FrameRenderOptions o = OptionsFor(wanted);
  pending_ = std::async(std::launch::async,
                        [this, camera, o] { return renderer_.Render(lf_, camera, o); });
  return ready;
}

bool FrameScheduler::converged(const ViewSettings& wanted) const {
  return !pending_.valid() && shown_scale_ >= 1 && shown_view_ && SameView(*shown_view_, wanted);
}

}  // namespace lfcam
