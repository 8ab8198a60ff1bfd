#include "lfcam/viewer/control_windows.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "lfcam/viewer/video_playback.h"
#include "lfcam/viewer/view_navigation.h"

namespace lfcam {
namespace {

bool DragVec3(const char* label, Vec3& v, float speed) {
  float f[3] = {float(v.x()), float(v.y()), float(v.z())};
  if (!ImGui::DragFloat3(label, f, speed, 0, 0, "%.1f")) return false;
  v = Vec3(f[0], f[1], f[2]);
  return true;
}

bool SliderLog(const char* label, double& value, double lo, double hi, const char* format) {
  float f = float(value);
  if (!ImGui::SliderFloat(label, &f, float(lo), float(hi), format, ImGuiSliderFlags_Logarithmic))
    return false;
  value = f;
  return true;
}

}  // namespace

bool DrawCameraWindow(ViewSettings& view, const LightField& lf, double rig_position[2],
                      bool* open) {
  const Slab& slab = lf.slab();
  const ArrayPlane& array = slab.uv;
  // The sliders span the light field's own scale (an imported one may be in assumed units).
  const double separation = std::max(std::abs(slab.separation_mm()), 1e-3);
  const double array_size = std::max(array.width_mm(), array.height_mm());
  // World lengths in the light field's unit (an import with no scale: the cameras' spacing,
  // WorldLengthUnit); the film's focal length is always in mm. The "###" ids keep each
  // widget's state whatever its label says.
  const std::string unit = WorldLengthUnit(lf.metadata());
  const auto label = [&](const char* name, const char* id) {
    return fmt::format("{} ({})###{}", name, unit, id);
  };
  bool changed = false;
  VirtualCameraParams& p = view.camera;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Camera (F2)", open, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::PushItemWidth(ImGui::GetFontSize() * 16);
    changed |= DragVec3(label("eye", "eye").c_str(), p.eye, unit == "mm" ? 2.0f : 0.02f);
    Vec3 forward = (p.look_at - p.eye).normalized();
    double yaw = std::atan2(forward.x(), -forward.z()) * 180 / M_PI;
    double pitch = std::asin(std::clamp(forward.y(), -1.0, 1.0)) * 180 / M_PI;
    float angles[2] = {float(yaw), float(pitch)};
    if (ImGui::DragFloat2("yaw, pitch (deg)", angles, 0.1f, -180, 180, "%.2f")) {
      const double y = angles[0] * M_PI / 180,
                   t = std::clamp(double(angles[1]), -89.0, 89.0) * M_PI / 180;
      forward = Vec3(std::sin(y) * std::cos(t), std::sin(t), -std::cos(y) * std::cos(t));
      p.look_at = p.eye + 1000.0 * forward;
      changed = true;
    }
    changed |= SliderLog("focal length f (mm)", p.focal_length_mm, 20, 2000, "%.1f");
    changed |= SliderLog(label("focus distance d_o", "d_o").c_str(), p.focus_distance_mm,
                         separation / 8, separation * 15, separation < 100 ? "%.2f" : "%.0f");
    changed |=
        SliderLog(label("aperture d_l", "d_l").c_str(), p.aperture_mm, 0, 4 * array_size, "%.2f");
    changed |= ImGui::Checkbox("focus breathing", &p.breathing);
    if (ImGui::Button("reset to the array's centre view (R)")) {
      p = ResetToArrayCentre(p, array);
      changed = true;
    }
    if (lf.has_view_cameras()) {
      // The rig's own cameras (render --as-camera): the photograph a camera took, or the image
      // a camera between them would.
      float at[2] = {float(rig_position[0]), float(rig_position[1])};
      ImGui::DragFloat2("rig camera (row, col)", at, 0.02f, 0.0f,
                        float(std::max(lf.dims().rows, lf.dims().cols) - 1), "%.2f");
      rig_position[0] = std::clamp(double(at[0]), 0.0, double(lf.dims().rows - 1));
      rig_position[1] = std::clamp(double(at[1]), 0.0, double(lf.dims().cols - 1));
      if (ImGui::Button("stand as the rig's camera")) {
        p = AsRigCamera(p, lf, rig_position[0], rig_position[1]);
        changed = true;
      }
    }
    p.focus_distance_mm = std::max(p.focus_distance_mm, MinFocusDistance(p));
    p.aperture_mm = std::max(p.aperture_mm, 0.0);
    ImGui::PopItemWidth();
  }
  ImGui::End();
  return changed;
}

std::string RenderModeName(const ViewSettings& view) {
  switch (view.integrator) {
    case Integrator::kCameras:
      return "cameras (exact limit)";
    case Integrator::kCamerasQuadrilinear:
      return "quadrilinear limit";
    case Integrator::kLensSamples:
      break;
  }
  return "lens samples, " + ToString(view.interpolation) + " lookup";
}

bool DrawRenderingWindow(ViewSettings& view, double& render_scale, const FrameStats& stats,
                         bool has_depth, bool* open) {
  bool changed = false;
  ImGui::SetNextWindowPos(ImVec2(10, ImGui::GetFontSize() * 17), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Rendering (F3)", open, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::PushItemWidth(ImGui::GetFontSize() * 16);
    const Integrator integrators[] = {Integrator::kLensSamples, Integrator::kCameras,
                                      Integrator::kCamerasQuadrilinear};
    int integrator =
        int(std::find(std::begin(integrators), std::end(integrators), view.integrator) -
            std::begin(integrators));
    if (ImGui::Combo("integrator", &integrator,
                     "lens samples (paper)\0cameras (exact limit)\0cameras, quadrilinear limit "
                     "(smooth)\0")) {
      view.integrator = integrators[integrator];
      changed = true;
    }
    const Interpolation lookups[] = {Interpolation::kQuadrilinear, Interpolation::kFocalPlane,
                                     Interpolation::kDepth};
    int lookup = int(std::find(std::begin(lookups), std::end(lookups), view.interpolation) -
                     std::begin(lookups));
    if (view.integrator == Integrator::kLensSamples &&
        ImGui::Combo("lookup", &lookup,
                     has_depth ? "quadrilinear (paper)\0focal plane\0depth (no ghosts)\0"
                               : "quadrilinear (paper)\0focal plane\0")) {
      view.interpolation = lookups[lookup];
      changed = true;
    }
    if (view.integrator == Integrator::kLensSamples) {
      float rate = float(view.camera.lens_rate);
      if (ImGui::SliderFloat("lens sampling rate", &rate, 0.25f, 16.0f, "%.2f",
                             ImGuiSliderFlags_Logarithmic)) {
        view.camera.lens_rate = rate;
        changed = true;
      }
    }
    float scale = float(render_scale);
    if (ImGui::SliderFloat("render scale", &scale, 0.1f, 2.0f, "%.2f")) {
      render_scale = scale;
      changed = true;
    }
    ImGui::Separator();
    ImGui::Text("backend: %s", stats.backend.c_str());
    ImGui::Text("frame: %d x %d%s", stats.width, stats.height,
                stats.scale < 1
                    ? fmt::format(" (reduced to {:.0f}% while moving)", 100 * stats.scale).c_str()
                    : "");
    if (stats.parts > 1)
      ImGui::Text("lens samples accumulated: part %d of %d", stats.parts_shown, stats.parts);
    ImGui::Text(
        "%.1f ms a frame%s", stats.frame_ms,
        stats.gpu_ms >= 0 ? fmt::format(" ({:.2f} ms on the GPU)", stats.gpu_ms).c_str() : "");
    if (stats.reads_per_pixel > 0 && view.integrator != Integrator::kLensSamples)
      ImGui::Text("%.1f cameras read a pixel", stats.reads_per_pixel);
    else if (stats.reads_per_pixel > 0)
      ImGui::Text("%.1f rays, %.1f camera lookups a pixel", stats.rays_per_pixel,
                  stats.reads_per_pixel);
    if (!stats.mode_ms.empty()) {
      // What each mode costs, as measured here at full resolution: to choose by.
      ImGui::Separator();
      ImGui::Text("a full frame, as last rendered:");
      for (const auto& [mode, ms] : stats.mode_ms) ImGui::Text("  %s: %.1f ms", mode.c_str(), ms);
    }
    if (!stats.status.empty()) ImGui::Text("%s", stats.status.c_str());
    ImGui::PopItemWidth();
  }
  ImGui::End();
  return changed;
}

bool DrawVideoWindow(VideoPlayback& playback, const PlaybackStats& stats, bool* open) {
  if (!*open || !playback.is_video()) return false;
  bool changed = false;
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(
      ImVec2(viewport->WorkPos.x + 10, viewport->WorkPos.y + viewport->WorkSize.y - 10),
      ImGuiCond_FirstUseEver, ImVec2(0, 1));
  ImGui::SetNextWindowSize(ImVec2(std::min(640.0f, viewport->WorkSize.x - 20), 0),
                           ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Video (F4)", open, ImGuiWindowFlags_NoSavedSettings)) {
    const std::int64_t n = playback.frames();
    if (ImGui::Button(playback.playing() ? "Pause" : "Play")) playback.Toggle();
    ImGui::SameLine();
    if (ImGui::Button("<")) {
      playback.Step(-1);
      changed = true;
    }
    ImGui::SameLine();
    if (ImGui::Button(">")) {
      playback.Step(1);
      changed = true;
    }
    ImGui::SameLine();
    bool loop = playback.loop();
    if (ImGui::Checkbox("loop", &loop)) playback.set_loop(loop);
    int frame = int(playback.playhead());
    ImGui::SetNextItemWidth(-1);
    if (ImGui::SliderInt("##timeline", &frame, 0, int(n - 1), "frame %d")) {
      playback.Seek(frame);
      changed = true;
    }
    ImGui::Text("frame %lld of %lld, %.3f s of %.3f s at %g fps", (long long)playback.playhead(),
                (long long)n, double(playback.playhead()) / playback.fps(),
                double(n) / playback.fps(), playback.fps());
    if (playback.playing())
      ImGui::Text("keeping %.1f of %g frames a second at %.0f%% resolution; %lld skipped",
                  stats.shown_fps, playback.fps(), 100.0 * stats.shown_scale,
                  (long long)playback.skipped());
    ImGui::Text("decoding %.1f ms a frame", playback.decode_ms());
    if (!playback.error().empty()) ImGui::TextWrapped("%s", playback.error().c_str());
  }
  ImGui::End();
  return changed;
}

void DrawHelpOverlay(bool* open) {
  if (!*open) return;
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(
      ImVec2(viewport->WorkPos.x + viewport->WorkSize.x - 10, viewport->WorkPos.y + 10),
      ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.75f);
  if (ImGui::Begin("Help (F1)", open,
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    static const char* const kLines[][2] = {
        {"F1", "this help"},
        {"F2 / F3 / F4", "Camera / Rendering / Video window"},
        {"space", "play / pause (a light field video)"},
        {", / .", "a frame back / on"},
        {"L", "loop on / off"},
        {"Home", "back to the first frame"},
        {"left drag", "orbit around the point in focus"},
        {"shift+left or middle drag", "pan"},
        {"wheel", "focus distance"},
        {"ctrl+wheel", "dolly (move forward and back)"},
        {"W A S D / Q E", "move forward, left, back, right / down, up"},
        {"Z / X", "zoom in / out (focal length)"},
        {"[ / ]", "aperture smaller / larger"},
        {"B", "focus breathing on / off"},
        {"click (no drag)", "focus on what is under the cursor"},
        {"R", "reset to the array's centre view"},
        {"F12", "screenshot: PNG and its view as JSON"},
        {"Esc", "quit"}};
    for (const auto& line : kLines) ImGui::Text("%-26s %s", line[0], line[1]);
  }
  ImGui::End();
}

}  // namespace lfcam
