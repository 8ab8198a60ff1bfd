#include "lfcam/node/simulated_camera.h"

#include <fmt/format.h>

#include <cmath>
#include <thread>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/node/jpeg_preview.h"
#include "lfcam/sim/capture_simulation.h"
#include "lfcam/sim/recording_clock.h"

namespace lfcam {

namespace {

std::int64_t SystemClockUnixNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

class SimulatedCamera final : public CameraBackend {
 public:
  explicit SimulatedCamera(const SimulatedCameraOptions& o)
      : options_(o), scene_(MakeScene(o.scene)) {
    if (o.rows < 1 || o.cols < 1 || o.row < 0 || o.col < 0 || o.row >= o.rows || o.col >= o.cols)
      throw Error(fmt::format("sim: position ({}, {}) is outside the {}x{} grid", o.row, o.col,
                              o.rows, o.cols));
    if (o.defects != "realistic" && o.defects != "none")
      throw Error(fmt::format("sim: defects '{}' is not realistic or none", o.defects));
    if (o.board != "chessboard" && o.board != "charuco")
      throw Error(fmt::format("sim: board '{}' is not chessboard or charuco", o.board));
  }

  std::string name() const override { return "sim"; }

  CameraProbe Probe() override {
    return {true,
            fmt::format("simulated Pi camera v1.3, {} scene, module ({}, {}) of {}x{}",
                        options_.scene, options_.row, options_.col, options_.rows, options_.cols),
            ""};
  }

  void Configure(const CaptureSettings& settings) override {
    CaptureSimulationOptions o;
    o.rows = options_.rows;
    o.cols = options_.cols;
    o.sensor_width = settings.width;
    o.sensor_height = settings.height;
    o.defects = options_.defects == "none" ? ModuleDefects::kNone : ModuleDefects::kRealistic;
    o.seed = options_.seed;
    o.intrinsics_board =
        ParseBoardSpec(options_.board == "charuco" ? kSimulatedCharuco : kSimulatedChessboard);
    o.noise = options_.noise;
    array_ = std::make_unique<SimulatedArray>(scene_, o);
    array_options_ = o;
    video_.reset();
    module_ = *array_->module_at(options_.row, options_.col);
    cache_ = {};
    quality_ = settings.jpeg_quality;
  }

  void Prepare(const ShotRequest& shot) override {
    if (!array_) throw Error("sim: the camera is not configured yet");
    const auto index = array_->shot_named(shot.shot);
    if (!index)
      throw Error(
          fmt::format("sim: the simulated array has no shot '{}' (scene, world, "
                      "shot_00..shot_{:02d})",
                      shot.shot, array_->shots().size() - 3));
    shot_ = *index;
  }

  void Fire() override {}

  // The image is rendered after the trigger: what the simulated module sees does not depend on
  // when, and the trigger stays as sharp as a real camera's.
  std::string Collect(std::chrono::milliseconds) override {
    const auto bytes = EncodeJpeg(array_->Expose(module_, shot_, cache_), quality_);
    return {bytes.begin(), bytes.end()};
  }

  void Record(const RecordRequest& request, const FrameSink& sink,
              const std::atomic<bool>& stop) override {
    if (!array_) throw Error("sim: the camera is not configured yet");
    const VideoRecordInfo& v = request.video;
    if (!video_ || video_->modules().front().intrinsics.width != v.width ||
        video_->modules().front().intrinsics.height != v.height) {
      CaptureSimulationOptions o = array_options_;
      o.sensor_width = v.width;
      o.sensor_height = v.height;
      video_ = std::make_unique<SimulatedArray>(scene_, o);
      video_cache_ = {};
    }
    RecordingClockOptions clock;
    clock.fps = v.fps;
    clock.sync = v.sync != "off";
    clock.clock_offset_s = options_.clock_offset_us * 1e-6;
    clock.drop_rate = options_.drop_rate;
    clock.seed = options_.seed;
    // The sync server's frames are the grid the others follow.
    const int node = v.sync == "server" ? 0 : 1 + options_.row * options_.cols + options_.col;
    const double stagger_s = double(v.stagger_ns) * 1e-9;
    for (const RecordedFrame& f : SimulateNodeFrames(node, v.seconds, clock)) {
      CapturedFrame frame;
      frame.sequence = f.sequence;
      frame.wall_clock_ns = request.start_unix_ns + std::llround((f.wall_clock + stagger_s) * 1e9);
      frame.sensor_ns = std::llround((f.sensor_timestamp + stagger_s) * 1e9);
      // A camera delivers a frame once it is exposed: not before the node's clock says so.
      while (!stop && SystemClockUnixNs() < frame.wall_clock_ns)
        std::this_thread::sleep_for(std::chrono::nanoseconds(
            std::min<std::int64_t>(frame.wall_clock_ns - SystemClockUnixNs(), 50'000'000)));
      if (stop) return;
      const auto bytes = EncodeJpeg(video_->ExposeAt(module_, f.exposure_start + stagger_s,
                                                     std::uint64_t(f.sequence), video_cache_),
                                    quality_);
      frame.jpeg.assign(bytes.begin(), bytes.end());
      sink(std::move(frame));
    }
  }

  std::string Preview(int max_width) override {
    if (!array_) throw Error("sim: the camera is not configured yet");
    Prepare({"preview", "scene", "scene"});
    return ScaledJpeg(Collect({}), max_width, 80, "the simulated frame");
  }

 private:
  SimulatedCameraOptions options_;
  Scene scene_;
  std::unique_ptr<SimulatedArray> array_, video_;  // the stills' sensor mode, the video's
  CaptureSimulationOptions array_options_;
  SimulatedArray::ModuleCache video_cache_;
  std::size_t module_ = 0, shot_ = 0;
  SimulatedArray::ModuleCache cache_;
  int quality_ = 95;
};

}  // namespace

std::unique_ptr<CameraBackend> MakeSimulatedCamera(const SimulatedCameraOptions& options) {
  return std::make_unique<SimulatedCamera>(options);
}

}  // namespace lfcam
