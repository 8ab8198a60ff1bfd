#include "lfcam/viewer/frame_scheduler.h"

#include <algorithm>
#include <cmath>

namespace lfcam {

bool SameView(const ViewSettings& a, const ViewSettings& b) {
  const VirtualCameraParams &p = a.camera, &q = b.camera;
  return p.width == q.width && p.height == q.height && p.eye == q.eye && p.look_at == q.look_at &&
         p.up == q.up && p.focal_length_mm == q.focal_length_mm &&
         p.focus_distance_mm == q.focus_distance_mm && p.aperture_mm == q.aperture_mm &&
         p.lens_rate == q.lens_rate && p.breathing == q.breathing &&
         p.principal_offset_px == q.principal_offset_px && a.integrator == b.integrator &&
         a.interpolation == b.interpolation;
}

VirtualCameraParams ScaledCamera(const VirtualCameraParams& camera, double scale) {
  VirtualCameraParams p = camera;
  if (scale >= 1) return p;
  const int width = std::max(16, int(std::lround(camera.width * scale)));
  return WithFrameSize(
      p, width, std::max(16, int(std::lround(double(width) * camera.height / camera.width))));
}

FrameScheduler::FrameScheduler(std::shared_ptr<const LightField> lf, const FrameRenderer& renderer,
                               FrameRenderOptions options, double budget_ms)
    : lf_(std::move(lf)),
      renderer_(renderer),
      options_(std::move(options)),
      budget_ms_(budget_ms) {}

void FrameScheduler::SetLightField(std::shared_ptr<const LightField> lf, std::int64_t index) {
  lf_ = std::move(lf);
  index_ = index;
}

bool FrameScheduler::Same(const ViewSettings& wanted) const {
  return shown_view_ && shown_index_ == index_ && SameView(*shown_view_, wanted);
}

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
  return renderer_.Render(*lf_, VirtualCamera(view.camera), OptionsFor(view));
}

void FrameScheduler::Finish(const Job& job, RenderResult result) {
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - job.start)
          .count();
  shown_view_ = job.view;
  shown_index_ = job.index;
  shown_scale_ = job.scale;
  parts_ = job.parts;
  parts_shown_ = job.part + 1;
  if (job.parts == 1) {
    shown_ms_ = ms;
    if (job.scale >= 1) full_ms_ = ms;
    shown_ = std::move(result);
    return;
  }
  if (job.part == 0) {
    accumulator_.Reset(job.view.camera.width, job.view.camera.height);
    parts_ms_ = 0;
  }
  accumulator_.Add(result);
  parts_ms_ += ms;
  shown_ = accumulator_.Frame();
  shown_.path = result.path;
  shown_ms_ = parts_ms_;
  shown_on_gl_ = false;
  if (parts_shown_ == parts_) full_ms_ = parts_ms_;
}

void FrameScheduler::Start(const Job& job) {
  VirtualCamera camera(ScaledCamera(job.view.camera, job.scale));
  if (job.parts > 1) {
    const int n = int(camera.lens_samples().size());
    camera = camera.WithLensSampleRange(n * job.part / job.parts, n * (job.part + 1) / job.parts);
  }
  const FrameRenderOptions o = OptionsFor(job.view);
  if (renderer_.uses_gl()) {
    RenderResult result;
    if (job.parts > 1) {
      result = renderer_.Render(*job.lf, camera, o);  // read back, to accumulate
    } else {
      // In the window's context: the frame stays in the renderer's output texture.
      result.gpu_ms = renderer_.gl()->RenderToTexture(*job.lf, camera, GlOptions(o));
      result.path = "gl (" + renderer_.gl()->device().renderer + ")";
      shown_on_gl_ = true;
    }
    Finish(job, std::move(result));
    return;
  }
  shown_on_gl_ = false;
  job_ = job;
  pending_ = std::async(std::launch::async, [this, camera, o, lf = job.lf] {
    return renderer_.Render(*lf, camera, o);
  });
}

bool FrameScheduler::Update(const ViewSettings& wanted, bool moving) {
  bool ready = false;
  if (pending_.valid() && pending_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    Finish(*job_, pending_.get());
    job_.reset();
    ready = true;
  }
  if (pending_.valid()) return ready;  // the worker is busy; the newest view comes next
  const bool same = Same(wanted);
  const auto now = std::chrono::steady_clock::now();
  // The next part of an accumulating frame.
  if (same && shown_scale_ >= 1 && parts_shown_ < parts_) {
    Start({wanted, lf_, index_, 1.0, parts_shown_, parts_, now});
    return true;
  }
  if (same && shown_scale_ >= 1) return ready;
  // Reduced while moving when a full frame would cost more than the budget.
  if (moving && full_ms_ > budget_ms_) {
    const double scale = std::clamp(std::sqrt(budget_ms_ / full_ms_), 0.125, 1.0);
    if (same && scale <= shown_scale_) return ready;  // nothing better to show yet
    Start({wanted, lf_, index_, scale, 0, 1, now});
    return true;
  }
  // At rest: the whole frame, in parts when it is a costly lens-samples one.
  int parts = 1;
  const VirtualCamera camera(wanted.camera);
  const int lens_samples = int(camera.lens_samples().size());
  if (wanted.integrator == Integrator::kLensSamples && lens_samples > 1 && full_ms_ > budget_ms_)
    parts = std::clamp(int(std::ceil(full_ms_ / budget_ms_)), 2, std::min(lens_samples, 64));
  Start({wanted, lf_, index_, 1.0, 0, parts, now});
  return true;
}

bool FrameScheduler::converged(const ViewSettings& wanted) const {
  return !pending_.valid() && shown_scale_ >= 1 && parts_shown_ == parts_ && Same(wanted);
}

}  // namespace lfcam
