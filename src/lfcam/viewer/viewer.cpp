#include "lfcam/viewer/viewer.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <chrono>
#include <cstdio>
#include <deque>
#include <memory>
#include <opencv2/core.hpp>
#include <thread>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/lightfield_video_file.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/render/focus_probe.h"
#include "lfcam/render/rig_camera.h"
#include "lfcam/viewer/control_windows.h"
#include "lfcam/viewer/frame_display.h"
#include "lfcam/viewer/frame_scheduler.h"
#include "lfcam/viewer/glfw_window.h"
#include "lfcam/viewer/video_playback.h"
#include "lfcam/viewer/view_navigation.h"
#include "lfcam/viewer/viewer_script.h"

namespace lfcam {
namespace {

using Clock = std::chrono::steady_clock;

class Viewer {
 public:
  Viewer(const ViewerOptions& options, std::unique_ptr<VideoPlayback> playback, DepthSet depth)
      : options_(options),
        playback_(std::move(playback)),
        depth_(std::move(depth)),
        window_(options.width, options.height, "lfcam view: " + options.light_field) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left behind
    float scale_x = 1, scale_y = 1;
    glfwGetWindowContentScale(window_.handle(), &scale_x, &scale_y);
    ImGui::GetStyle().ScaleAllSizes(scale_x);
    ImGui::GetIO().FontGlobalScale = scale_x;
    ImGui_ImplGlfw_InitForOpenGL(window_.handle(), true);  // chains the callbacks above
    ImGui_ImplOpenGL3_Init("#version 330 core");
    display_ = std::make_unique<FrameDisplay>();
    renderer_ = std::make_unique<FrameRenderer>(options.backend, true);
    renderer_->KeepPrefilteredViews();  // on the CPU; the GL renderer keeps its own
    FrameRenderOptions render_options;
    render_options.threads = options.threads;
    render_options.workgroup_x = options.workgroup_x;
    render_options.workgroup_y = options.workgroup_y;
    if (depth_.count() > 0) render_options.depth = &depth_;
    scheduler_ = std::make_unique<FrameScheduler>(playback_->current(), *renderer_, render_options,
                                                  options.frame_budget_ms);
    scheduler_->SetLightField(playback_->current(), playback_->current_index());
    render_scale_ = options.render_scale;
    if (!options.view_file.empty()) {
      view_ = ReadViewFile(options.view_file);
    } else {
      view_.camera = StartingView(lf(), view_.camera.width, view_.camera.height);
      rig_position_[0] = 0.5 * (lf().dims().rows - 1);  // where StartingView stands
      rig_position_[1] = 0.5 * (lf().dims().cols - 1);
      // A smooth out-of-focus blur (the focal-plane limit, Integrator::kCameras, shows a lattice
      // of the cameras' copies there): the paper's estimator's limit, noise-free, on either
      // renderer. On the CPU its filtered views are kept from frame to frame
      // (render/prefilter_cache.h), so a frame at the same focus costs about what the cameras
      // integrator's does (docs/viewer.md).
      view_.integrator = Integrator::kCamerasQuadrilinear;
    }
    view_.light_field = options.light_field;
    stats_.backend = renderer_->description();
    std::printf("lfcam view: %s\n", stats_.backend.c_str());
    std::fflush(stdout);
  }

  ~Viewer() {
    scheduler_.reset();
    renderer_.reset();
    display_.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }

  void Run() {
    std::vector<ScriptCommand> script;
    if (!options_.script.empty()) script = ReadViewerScript(options_.script);
    std::size_t next = 0;
    while (!glfwWindowShouldClose(window_.handle())) {
      glfwPollEvents();
      FitViewToFramebuffer();
      HandleInput();
      AdvanceVideo();
      // A script command runs when the one before it is done (wait: the frame converged).
      while (next < script.size() && !waiting_ && wait_frame_ < 0 && frames_left_ == 0) {
        if (!RunCommand(script[next++])) return;
        FitViewToFramebuffer();
        AdvanceVideo();
      }
      if (waiting_ && scheduler_->converged(view_) && !moving()) waiting_ = false;
      if (wait_frame_ >= 0 && scheduler_->shown_index() == wait_frame_) wait_frame_ = -1;
      if (frames_left_ > 0) --frames_left_;
      DrawFrame();
      if (!script.empty() && next >= script.size() && !waiting_ && wait_frame_ < 0 &&
          frames_left_ == 0)
        return;
    }
  }

 private:
  const LightField& lf() const { return *playback_->current(); }

  // A playing video counts as moving: on the CPU its frames render reduced when a full one would
  // not fit the frame period (resolution drops before frames do).
  bool moving() const {
    return playback_->playing() || Clock::now() - last_change_ < std::chrono::milliseconds(250);
  }

  // The video's clock moves the playhead; a new frame goes to the scheduler.
  void AdvanceVideo() {
    const double period_ms = 1000.0 / std::max(1e-3, playback_->fps());
    scheduler_->set_budget_ms(playback_->playing() ? std::min(options_.frame_budget_ms, period_ms)
                                                   : options_.frame_budget_ms);
    if (playback_->Tick())
      scheduler_->SetLightField(playback_->current(), playback_->current_index());
  }

  void Changed() { last_change_ = Clock::now(); }

  // The render resolution follows the window's framebuffer and the render scale.
  void FitViewToFramebuffer() {
    glfwGetFramebufferSize(window_.handle(), &fb_width_, &fb_height_);
    const int w = std::max(16, int(std::lround(fb_width_ * render_scale_)));
    const int h = std::max(16, int(std::lround(fb_height_ * render_scale_)));
    if (w != view_.camera.width || h != view_.camera.height) {
      view_.camera = WithFrameSize(view_.camera, w, h);
      Changed();
    }
  }

  void SetView(VirtualCameraParams p) {
    p.lens_length_scale = LensLengthScale(lf());  // the light field's, whatever the view's
    try {
      VirtualCamera check(p);  // refuse a view the camera cannot take (for example f >= d_o)
      view_.camera = p;
      Changed();
    } catch (const Error& e) {
      stats_.status = e.what();
    }
  }

  // Window pixel (top-left origin, screen coordinates) to film position (bottom-left, pixels).
  void FilmPosition(double x, double y, double* fx, double* fy) const {
    int ww = 1, wh = 1;
    glfwGetWindowSize(window_.handle(), &ww, &wh);
    *fx = x / std::max(ww, 1) * view_.camera.width;
    *fy = (1.0 - y / std::max(wh, 1)) * view_.camera.height;
  }

  void ClickToFocus(double x, double y) {
    double fx = 0, fy = 0;
    FilmPosition(x, y, &fx, &fy);
    const FocusProbe probe = ProbeFocusDistance(lf(), VirtualCamera(view_.camera), fx, fy);
    if (!probe.found) {
      stats_.status = fmt::format("focus: no camera sees ({:.0f}, {:.0f})", x, y);
    } else {
      VirtualCameraParams p = view_.camera;
      p.focus_distance_mm = std::max(probe.focus_distance_mm, MinFocusDistance(p));
      SetView(p);
      const std::string unit = WorldLengthUnit(lf().metadata());
      stats_.status =
          fmt::format("focus: {:.{}f} {} at ({:.0f}, {:.0f}), confidence {:.2f}, {} cameras",
                      probe.focus_distance_mm, unit == "mm" ? 0 : 2, unit, x, y, probe.confidence,
                      probe.cameras);
    }
    std::printf("%s\n", stats_.status.c_str());
    std::fflush(stdout);
  }

  void Drag(double dx, double dy, bool pan) {
    if (pan) {
      const double mm =
          MmPerPixelAtFocus(view_.camera) * view_.camera.width / std::max(1, WindowWidth());
      SetView(Move(view_.camera, -dx * mm, dy * mm, 0));
    } else {
      // A drag across the window swings the eye across about the array's width: a light field
      // is seen from near its array only.
      const ArrayPlane& array = lf().slab().uv;
      const double radians_per_pixel = std::max(array.width_mm(), array.height_mm()) /
                                       view_.camera.focus_distance_mm / std::max(1, WindowWidth());
      SetView(Orbit(view_.camera, dx * radians_per_pixel, -dy * radians_per_pixel));
    }
  }

  int WindowWidth() const {
    int ww = 1, wh = 1;
    glfwGetWindowSize(window_.handle(), &ww, &wh);
    return ww;
  }

  void Screenshot(const std::string& png) {
    // The frame on screen when it is the view at full quality and on the CPU (an accumulated
    // one included); else rendered now.
    const bool shown =
        scheduler_->converged(view_) && !scheduler_->on_gl() && !scheduler_->shown().image.empty();
    const RenderResult frame = shown ? scheduler_->shown() : scheduler_->RenderNow(view_);
    WriteImage(png, frame.image);
    std::string json = png;
    const auto dot = json.rfind('.');
    json = (dot == std::string::npos ? json : json.substr(0, dot)) + ".json";
    WriteViewFile(json, view_);
    stats_.status = "saved " + png + " and " + json;
    if (shown && scheduler_->parts() > 1)
      stats_.status += fmt::format(" (lens samples accumulated in {} parts)", scheduler_->parts());
    std::printf("%s\n", stats_.status.c_str());
    std::fflush(stdout);
  }

  void PressKey(int key) {
    VirtualCameraParams p = view_.camera;
    switch (key) {
      case GLFW_KEY_F1:
        panels_.help = !panels_.help;
        break;
      case GLFW_KEY_F2:
        panels_.camera = !panels_.camera;
        break;
      case GLFW_KEY_F3:
        panels_.rendering = !panels_.rendering;
        break;
      case GLFW_KEY_F4:
        panels_.video = !panels_.video;
        break;
      case GLFW_KEY_SPACE:
        playback_->Toggle();
        break;
      case GLFW_KEY_COMMA:
        playback_->Step(-1);
        break;
      case GLFW_KEY_PERIOD:
        playback_->Step(1);
        break;
      case GLFW_KEY_L:
        playback_->set_loop(!playback_->loop());
        break;
      case GLFW_KEY_HOME:
        playback_->Seek(0);
        break;
      case GLFW_KEY_F12:
        Screenshot(fmt::format("{}_{:03d}.png", options_.screenshot_prefix, ++screenshots_));
        break;
      case GLFW_KEY_R:
        SetView(ResetToArrayCentre(p, lf().slab().uv));
        break;
      case GLFW_KEY_Z:
        SetView(ScaleFocalLength(p, 1.1));
        break;
      case GLFW_KEY_X:
        SetView(ScaleFocalLength(p, 1 / 1.1));
        break;
      case GLFW_KEY_LEFT_BRACKET:
        p.aperture_mm = p.aperture_mm / 1.2;
        SetView(p);
        break;
      case GLFW_KEY_RIGHT_BRACKET:
        p.aperture_mm = std::max(4.0, p.aperture_mm * 1.2);
        SetView(p);
        break;
      case GLFW_KEY_B:
        p.breathing = !p.breathing;
        SetView(p);
        break;
      case GLFW_KEY_ESCAPE:
        glfwSetWindowShouldClose(window_.handle(), GLFW_TRUE);
        break;
      default:
        break;
    }
  }

  void HandleInput() {
    const ImGuiIO& io = ImGui::GetIO();
    const WindowInput input = window_.TakeInput();
    const std::vector<int>& keys = input.keys_pressed;
    const double scroll = input.scroll;
    if (!io.WantCaptureKeyboard)
      for (const int key : keys) PressKey(key);
    // Held keys move the eye: 300 mm a second.
    const double now = glfwGetTime();
    const double dt = std::min(now - last_time_, 0.1);
    last_time_ = now;
    if (!io.WantCaptureKeyboard) {
      const auto held = [&](int key) { return glfwGetKey(window_.handle(), key) == GLFW_PRESS; };
      const double step = 300.0 * dt;
      const double right = (held(GLFW_KEY_D) - held(GLFW_KEY_A)) * step;
      const double up = (held(GLFW_KEY_E) - held(GLFW_KEY_Q)) * step;
      const double forward = (held(GLFW_KEY_W) - held(GLFW_KEY_S)) * step;
      if (right != 0 || up != 0 || forward != 0) SetView(Move(view_.camera, right, up, forward));
    }
    if (io.WantCaptureMouse) {
      dragging_ = false;
      return;
    }
    const bool ctrl = glfwGetKey(window_.handle(), GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                      glfwGetKey(window_.handle(), GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    if (scroll != 0) {
      if (ctrl)
        SetView(Move(view_.camera, 0, 0, scroll * 0.05 * view_.camera.focus_distance_mm));
      else
        SetView(ScaleFocusDistance(view_.camera, std::pow(1.03, scroll)));
    }
    double x = 0, y = 0;
    glfwGetCursorPos(window_.handle(), &x, &y);
    const bool left = glfwGetMouseButton(window_.handle(), GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool middle =
        glfwGetMouseButton(window_.handle(), GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    const bool shift = glfwGetKey(window_.handle(), GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                       glfwGetKey(window_.handle(), GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    if (left || middle) {
      if (!dragging_) {
        dragging_ = true;
        drag_moved_ = false;
        press_x_ = x;
        press_y_ = y;
      } else if (x != last_x_ || y != last_y_) {
        if (std::hypot(x - press_x_, y - press_y_) > 3) drag_moved_ = true;
        if (drag_moved_) Drag(x - last_x_, y - last_y_, middle || shift);
      }
    } else if (dragging_) {
      dragging_ = false;
      if (!drag_moved_) ClickToFocus(press_x_, press_y_);  // a click, not a drag
    }
    last_x_ = x;
    last_y_ = y;
  }

  // Runs one script command; false: quit.
  bool RunCommand(const ScriptCommand& c) {
    const auto number = [&](std::size_t i) { return std::stod(c.args[i]); };
    const std::string where = fmt::format("{}:{}", options_.script, c.line);
    try {
      if (c.name == "quit") return false;
      if (c.name == "window") {
        glfwSetWindowSize(window_.handle(), int(number(0)), int(number(1)));
        frames_left_ = 3;  // let the window system apply it
      } else if (c.name == "set") {
        SetParameter(c.args[0], c.args[1]);
      } else if (c.name == "click") {
        ClickToFocus(number(0), number(1));
      } else if (c.name == "drag") {
        const bool pan = c.args.size() > 4 && (c.args[4] == "middle" || c.args[4] == "shift");
        Drag(number(2) - number(0), number(3) - number(1), pan);
      } else if (c.name == "key") {
        PressKey(GlfwKeyFromName(c.args[0]));
      } else if (c.name == "wait") {
        waiting_ = true;
        last_change_ = Clock::now() - std::chrono::seconds(1);  // scripted changes rest at once
      } else if (c.name == "frames") {
        frames_left_ = std::max(0, int(number(0)));
      } else if (c.name == "screenshot") {
        Screenshot(c.args[0]);
      } else if (c.name == "capture") {
        RequireImageOutput(c.args[0], "capture");
        capture_path_ = c.args[0];
        frames_left_ = 1;  // taken as the next frame is drawn
      } else if (c.name == "camera") {
        rig_position_[0] = number(0);
        rig_position_[1] = number(1);
        SetView(AsRigCamera(view_.camera, lf(), number(0), number(1)));
      } else if (c.name == "print") {
        nlohmann::json j = ViewToJson(view_);
        if (playback_->is_video())
          j["video"] = {
              {"frame", scheduler_->shown_index()},    {"frames", playback_->frames()},
              {"playing", playback_->playing()},       {"skipped", playback_->skipped()},
              {"kept_fps", playback_stats_.shown_fps}, {"scale", scheduler_->shown_scale()}};
        std::printf("%s\n", j.dump().c_str());
        std::fflush(stdout);
      } else if (c.name == "play") {
        playback_->Play();
      } else if (c.name == "pause") {
        playback_->Pause();
      } else if (c.name == "seek") {
        playback_->Seek(std::int64_t(number(0)));
      } else if (c.name == "step") {
        playback_->Step(std::int64_t(number(0)));
      } else if (c.name == "loop") {
        playback_->set_loop(c.args[0] == "on");
      } else if (c.name == "wait-frame") {
        wait_frame_ = std::int64_t(number(0));
        if (wait_frame_ < 0 || wait_frame_ >= playback_->frames())
          throw Error(fmt::format("wait-frame {}: the video has {} frames", wait_frame_,
                                  playback_->frames()));
      }
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    } catch (const std::exception& e) {
      throw Error(where + ": " + e.what());
    }
    return true;
  }

  void SetParameter(const std::string& name, const std::string& value) {
    VirtualCameraParams p = view_.camera;
    const auto number = [&] {
      std::size_t used = 0;
      const double v = std::stod(value, &used);
      if (used != value.size() || !std::isfinite(v)) throw Error("'" + value + "' is not a number");
      return v;
    };
    const auto vec3 = [&] {
      double x = 0, y = 0, z = 0;
      char a = 0, b = 0;
      std::istringstream in(value);
      if (!(in >> x >> a >> y >> b >> z) || a != ',' || b != ',')
        throw Error("'" + value + "' is not X,Y,Z");
      return Vec3(x, y, z);
    };
    if (name == "focal-length")
      p.focal_length_mm = number();
    else if (name == "focus-distance")
      p.focus_distance_mm = number();
    else if (name == "aperture")
      p.aperture_mm = number();
    else if (name == "lens-rate")
      p.lens_rate = number();
    else if (name == "eye")
      p.eye = vec3();
    else if (name == "look-at")
      p.look_at = vec3();
    else if (name == "up")
      p.up = vec3();
    else if (name == "breathing") {
      if (value != "on" && value != "off") throw Error("breathing is on or off");
      p.breathing = value == "on";
    } else if (name == "integrator") {
      view_.integrator = IntegratorFromString(value);
    } else if (name == "interpolation") {
      const Interpolation interpolation = InterpolationFromString(value);
      if (interpolation == Interpolation::kDepth && depth_.count() == 0)
        throw Error("the depth lookup needs the views' depth maps: open the viewer with --depth");
      view_.interpolation = interpolation;
    } else if (name == "scale") {
      const double s = number();
      if (!(s >= 0.05 && s <= 2)) throw Error("scale must be 0.05 to 2");
      render_scale_ = s;
    } else {
      throw Error("unknown parameter '" + name + "'");
    }
    VirtualCamera check(p);  // throws with the reason when the camera cannot be
    view_.camera = p;
    Changed();
  }

  void DrawFrame() {
    if (scheduler_->Update(view_, moving()) && !scheduler_->on_gl() &&
        !scheduler_->shown().image.empty())
      display_->Upload(scheduler_->shown().image);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    stats_.frame_ms = scheduler_->shown_ms();
    stats_.gpu_ms = scheduler_->shown().gpu_ms;
    stats_.scale = scheduler_->shown_scale();
    stats_.parts_shown = scheduler_->parts_shown();
    stats_.parts = scheduler_->parts();
    stats_.width = view_.camera.width;
    stats_.height = view_.camera.height;
    const RenderResult& shown = scheduler_->shown();
    if (scheduler_->shown_view() && stats_.scale >= 1 && stats_.parts_shown == stats_.parts &&
        scheduler_->full_estimate_ms() > 0)
      stats_.mode_ms[RenderModeName(*scheduler_->shown_view())] = scheduler_->full_estimate_ms();
    const double pixels = std::max(1.0, double(shown.image.total()));
    stats_.rays_per_pixel = shown.image.empty() ? 0 : double(shown.rays) / pixels;
    stats_.reads_per_pixel = shown.image.empty()
                                 ? 0
                                 : (view_.integrator != Integrator::kLensSamples ? 1.0 : 4.0) *
                                       double(shown.rays_hit) / pixels;
    bool changed = false;
    if (scheduler_->shown_index() != last_drawn_index_) {
      // The frame rate kept: light field frames drawn over the last second.
      last_drawn_index_ = scheduler_->shown_index();
      const auto now = Clock::now();
      drawn_at_.push_back(now);
      while (!drawn_at_.empty() && now - drawn_at_.front() > std::chrono::seconds(1))
        drawn_at_.pop_front();
    }
    playback_stats_.shown_fps = double(drawn_at_.size());
    playback_stats_.shown_scale = scheduler_->shown_scale();
    playback_stats_.shown = scheduler_->shown_index();
    if (panels_.camera) changed |= DrawCameraWindow(view_, lf(), rig_position_, &panels_.camera);
    if (panels_.rendering)
      changed |=
          DrawRenderingWindow(view_, render_scale_, stats_, depth_.count() > 0, &panels_.rendering);
    if (DrawVideoWindow(*playback_, playback_stats_, &panels_.video)) AdvanceVideo();
    DrawHelpOverlay(&panels_.help);
    if (changed) Changed();
    ImGui::Render();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glClearColor(0.1f, 0.1f, 0.1f, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    if (scheduler_->shown_scale() > 0) {
      const unsigned texture =
          scheduler_->on_gl() ? renderer_->gl()->output_texture() : display_->uploaded_texture();
      display_->Draw(texture, !scheduler_->on_gl(), fb_width_, fb_height_);
    }
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (!capture_path_.empty()) CaptureWindow();
    glfwSwapBuffers(window_.handle());
  }

  // The window's framebuffer as drawn (before the swap), to an 8-bit sRGB image.
  void CaptureWindow() {
    cv::Mat rgb(fb_height_, fb_width_, CV_8UC3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, fb_width_, fb_height_, GL_RGB, GL_UNSIGNED_BYTE, rgb.data);
    cv::flip(rgb, rgb, 0);
    WriteImage(capture_path_, rgb);
    std::printf("captured the window in %s\n", capture_path_.c_str());
    std::fflush(stdout);
    capture_path_.clear();
  }

  const ViewerOptions& options_;
  std::unique_ptr<VideoPlayback> playback_;  // a still plays as a video of one frame
  DepthSet depth_;                           // empty without --depth
  GlfwWindow window_;
  std::unique_ptr<FrameDisplay> display_;
  std::unique_ptr<FrameRenderer> renderer_;
  std::unique_ptr<FrameScheduler> scheduler_;
  ViewSettings view_;
  double render_scale_ = 1;
  PanelVisibility panels_;
  double rig_position_[2] = {0, 0};  // the Camera window's rig camera (row, col)
  FrameStats stats_;
  int fb_width_ = 1, fb_height_ = 1;
  Clock::time_point last_change_ = Clock::now();
  double last_time_ = 0;
  bool dragging_ = false, drag_moved_ = false;
  double press_x_ = 0, press_y_ = 0, last_x_ = 0, last_y_ = 0;
  bool waiting_ = false;
  int frames_left_ = 0;
  std::int64_t wait_frame_ = -1, last_drawn_index_ = -1;
  std::deque<Clock::time_point> drawn_at_;
  PlaybackStats playback_stats_;
  int screenshots_ = 0;
  std::string capture_path_;
};

}  // namespace

void RunViewer(const ViewerOptions& options) {
  // Everything that can be wrong with the inputs is found before a window opens. A light field
  // video opens at its first frame, paused.
  auto playback = std::make_unique<VideoPlayback>(options.light_field);
  if (!options.script.empty()) ReadViewerScript(options.script);
  if (!options.view_file.empty()) ReadViewFile(options.view_file);
  DepthSet depth;
  if (!options.depth_dir.empty()) {
    if (playback->frames() > 1)
      throw Error(
          fmt::format("--depth {}: depth maps belong to one light field frame, and {} is a "
                      "video of {} frames",
                      options.depth_dir, options.light_field, playback->frames()));
    depth = ReadDepthSet(options.depth_dir, *playback->current(), DepthsForRendering());
  }
  Viewer viewer(options, std::move(playback), std::move(depth));
  viewer.Run();
}

}  // namespace lfcam
