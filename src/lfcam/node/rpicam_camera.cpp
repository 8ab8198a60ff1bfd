#include "lfcam/node/rpicam_camera.h"

#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/node/jpeg_preview.h"
#include "lfcam/node/program_output.h"
#include "lfcam/node/rpicam_video.h"

extern char** environ;

namespace lfcam {

namespace {

namespace fs = std::filesystem;

class RpicamCamera final : public CameraBackend {
 public:
  explicit RpicamCamera(RpicamOptions options) : options_(std::move(options)) {
    if (options_.program.empty())
      options_.program = FindOnPath({"rpicam-still", "libcamera-still"});
    if (options_.video_program.empty())
      options_.video_program = FindOnPath({"rpicam-vid", "libcamera-vid"});
    std::error_code ec;
    fs::create_directories(options_.work_folder, ec);
    if (ec)
      throw Error(fmt::format("{}: cannot create the camera's work folder: {}",
                              options_.work_folder.string(), ec.message()));
  }
  ~RpicamCamera() override { Stop(); }

  std::string name() const override { return "rpicam"; }

  CameraProbe Probe() override {
    if (options_.program.empty())
      return {false, "rpicam", "neither rpicam-still nor libcamera-still is on PATH"};
    if (pid_ > 0 && !Running())
      return {false, options_.program, fmt::format("the camera process exited ({})", exit_)};
    return {true, options_.program,
            fmt::format("{}; video: {}", pid_ > 0 ? "running, settings locked" : "not started",
                        VideoAbility())};
  }

  // What recording can do here: rpicam-vid with libcamera's sync (rpicam-apps 1.6 and later), or
  // without it (a scheduled start only), or none.
  std::string VideoAbility() {
    if (options_.video_program.empty()) return "none (no rpicam-vid or libcamera-vid on PATH)";
    return SyncSupported() ? options_.video_program + " with --sync"
                           : options_.video_program +
                                 " without --sync (rpicam-apps before 1.6): recordings start at a "
                                 "scheduled time only";
  }

  // Whether the video program knows --sync (asked once: its --help).
  bool SyncSupported() {
    if (!sync_supported_) {
      const std::string help =
          RunProgram({options_.video_program, "--help"}, /*with_stderr=*/true).output;
      sync_supported_ = help.find("--sync") != std::string::npos;
    }
    return *sync_supported_;
  }

  void Configure(const CaptureSettings& settings) override {
    // Checked now, so that a bad template is refused at configure time.
    ExpandCameraCommand(options_.command, options_.program, settings, Output());
    settings_ = settings;
    configured_ = true;
    Stop();
  }

  void Prepare(const ShotRequest&) override {
    if (!configured_) throw Error("rpicam: the camera is not configured yet");
    if (options_.program.empty())
      throw Error("rpicam: neither rpicam-still nor libcamera-still is on PATH");
    if (pid_ <= 0 || !Running()) Start();
    const auto ready = started_ + std::chrono::milliseconds(options_.warmup_ms);
    std::this_thread::sleep_until(ready);
    before_ = Frames();
  }

  void Fire() override {
    if (pid_ > 0) ::kill(pid_, SIGUSR1);
  }

  std::string Collect(std::chrono::milliseconds timeout) override {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::optional<fs::path> frame;
    std::uintmax_t last_size = 0;
    while (std::chrono::steady_clock::now() < deadline) {
      if (!frame) {
        for (const fs::path& f : Frames())
          if (!before_.count(f)) frame = f;
      }
      if (frame) {
        // Written completely when its size stops changing.
        std::error_code ec;
        const auto size = fs::file_size(*frame, ec);
        if (!ec && size > 0 && size == last_size) {
          const auto bytes = ReadFileBytes(*frame, std::uint64_t(1) << 30, "camera frame");
          fs::remove(*frame, ec);
          return {bytes.begin(), bytes.end()};
        }
        last_size = ec ? 0 : size;
      } else if (!Running()) {
        throw Error(
            fmt::format("rpicam: the camera process exited ({}) before writing a frame", exit_));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    throw Error(
        fmt::format("rpicam: no frame from {} within {} ms", options_.program, timeout.count()));
  }

  std::chrono::milliseconds RecordLead(const VideoRecordInfo& video) const override {
    const double frames = video.sync == "off" ? 0 : options_.sync_warmup_frames;
    return std::chrono::milliseconds(options_.warmup_ms + std::int64_t(1000 * frames / video.fps));
  }

  void Record(const RecordRequest& request, const FrameSink& sink,
              const std::atomic<bool>& stop) override {
    if (!configured_) throw Error("rpicam: the camera is not configured yet");
    if (options_.video_program.empty())
      throw Error("rpicam: neither rpicam-vid nor libcamera-vid is on PATH");
    const VideoRecordInfo& v = request.video;
    if (v.stagger_ns != 0)
      throw Error(
          "rpicam: a staggered recording needs each group's frames offset from the sync "
          "server's, which libcamera's software sync does not do (docs/hardware.md, high-speed "
          "mode)");
    Stop();  // the stills' camera lets go of the sensor
    const fs::path stream = options_.work_folder / "video.mjpeg";
    const fs::path metadata = options_.work_folder / "video.json";
    std::error_code ec;
    fs::remove(stream, ec);
    fs::remove(metadata, ec);
    CaptureSettings s = settings_;
    s.width = v.width;
    s.height = v.height;
    // Start the camera early enough that it records from the start time, and let it run a few
    // frames past the end.
    const auto lead = RecordLead(v);
    const std::int64_t start = request.start_unix_ns;
    const std::int64_t launch = start - std::int64_t(lead.count()) * 1'000'000;
    while (!stop && WallNs() < launch)
      std::this_thread::sleep_for(std::chrono::milliseconds(
          std::min<std::int64_t>(50, std::max<std::int64_t>(1, (launch - WallNs()) / 1'000'000))));
    if (stop) return;
    VideoCommandValues values;
    values.fps = v.fps;
    values.metadata = metadata.string();
    // Without libcamera's sync (older rpicam-apps) every node starts at the scheduled time.
    values.sync = SyncSupported() ? v.sync : "off";
    const double period_s = 1.0 / v.fps;
    values.timeout_ms =
        std::int64_t(std::ceil((double(start - WallNs()) / 1e9 + v.seconds + 3 * period_s) * 1000));
    Spawn(ExpandCameraCommand(options_.video_command, options_.video_program, s, stream.string(),
                              &values));
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(values.timeout_ms + 10'000);
    while (Running()) {
      if (stop || std::chrono::steady_clock::now() > deadline) {
        Stop();
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (!fs::is_regular_file(stream, ec))
      throw Error(fmt::format("rpicam: {} wrote no video ({})", options_.video_program, exit_));
    const auto bytes = ReadFileBytes(stream, std::uint64_t(1) << 40, "video stream");
    const std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    const auto jpegs = SplitMjpeg(all, stream.string());
    const auto text = ReadFileBytes(metadata, std::uint64_t(1) << 32, "video metadata");
    const auto times = ParseRpicamMetadata(
        {reinterpret_cast<const char*>(text.data()), text.size()}, metadata.string());
    const std::size_t n = std::min(jpegs.size(), times.size());
    const std::vector<RpicamFrameTime> paired(times.begin(), times.begin() + std::ptrdiff_t(n));
    const std::vector<std::int64_t> sequence = SequenceFromSensorTimes(paired, v.fps);
    // The recording's frames: those whose exposures start within [T, T + seconds), each on the
    // grid to within half a period.
    const auto half = std::int64_t(period_s * 0.5e9);
    const std::int64_t end = start + std::int64_t(v.seconds * 1e9);
    std::int64_t first = -1;
    for (std::size_t i = 0; i < n; ++i) {
      if (paired[i].wall_clock_ns < start - half || paired[i].wall_clock_ns >= end - half) continue;
      if (first < 0) first = sequence[i];
      CapturedFrame f;
      f.sequence = sequence[i] - first;
      f.wall_clock_ns = paired[i].wall_clock_ns;
      f.sensor_ns = paired[i].sensor_ns;
      f.jpeg.assign(all.substr(jpegs[i].first, jpegs[i].second));
      sink(std::move(f));
    }
    if (first < 0)
      throw Error(
          fmt::format("rpicam: {} recorded {} frames, none within the recording's time "
                      "(is the clock right?)",
                      options_.video_program, n));
  }

  std::string Preview(int max_width) override {
    Prepare({"preview", "preview", "preview"});
    Fire();
    return ScaledJpeg(Collect(std::chrono::seconds(10)), max_width, 80, "the camera's frame");
  }

 private:
  std::string Output() const { return (options_.work_folder / "frame%05d.jpg").string(); }

  std::set<fs::path> Frames() const {
    std::set<fs::path> out;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(options_.work_folder, ec))
      if (entry.path().extension() == ".jpg") out.insert(entry.path());
    return out;
  }

  void Start() {
    Stop();
    // Frames left from an earlier run would be mistaken for new ones.
    std::error_code ec;
    for (const fs::path& f : Frames()) fs::remove(f, ec);
    Spawn(ExpandCameraCommand(options_.command, options_.program, settings_, Output()));
  }

  static std::int64_t WallNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
  }

  void Spawn(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int rc = ::posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
    if (rc != 0)
      throw Error(fmt::format("rpicam: cannot start {}: {}", args[0], std::strerror(rc)));
    pid_ = pid;
    exit_.clear();
    started_ = std::chrono::steady_clock::now();
  }

  bool Running() {
    if (pid_ <= 0) return false;
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == 0) return true;
    exit_ = WIFEXITED(status)     ? fmt::format("exit status {}", WEXITSTATUS(status))
            : WIFSIGNALED(status) ? fmt::format("signal {}", WTERMSIG(status))
                                  : "gone";
    pid_ = -1;
    return false;
  }

  void Stop() {
    if (pid_ <= 0) return;
    // rpicam-apps quit cleanly on SIGUSR2; then SIGTERM, then SIGKILL.
    for (int sig : {SIGUSR2, SIGTERM, SIGKILL}) {
      ::kill(pid_, sig);
      for (int i = 0; i < 50 && Running(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (pid_ <= 0) return;
    }
  }

  RpicamOptions options_;
  CaptureSettings settings_;
  bool configured_ = false;
  pid_t pid_ = -1;
  std::string exit_;
  std::chrono::steady_clock::time_point started_;
  std::set<fs::path> before_;
  std::optional<bool> sync_supported_;
};

}  // namespace

std::vector<std::string> ExpandCameraCommand(const std::string& command_template,
                                             const std::string& program, const CaptureSettings& s,
                                             const std::string& output,
                                             const VideoCommandValues* video) {
  const VideoCommandValues none;
  const VideoCommandValues& v = video ? *video : none;
  const std::pair<const char*, std::string> values[] = {
      {"{fps}", fmt::format("{}", v.fps)},
      {"{timeout_ms}", std::to_string(v.timeout_ms)},
      {"{metadata}", v.metadata},
      {"{program}", program},
      {"{width}", std::to_string(s.width)},
      {"{height}", std::to_string(s.height)},
      {"{exposure_us}", std::to_string(s.exposure_us)},
      {"{analogue_gain}", fmt::format("{}", s.analogue_gain)},
      {"{awb_red}", fmt::format("{}", s.awb_red)},
      {"{awb_blue}", fmt::format("{}", s.awb_blue)},
      {"{denoise}", s.denoise},
      {"{jpeg_quality}", std::to_string(s.jpeg_quality)},
      {"{output}", output}};
  std::vector<std::string> args;
  std::stringstream words(command_template);
  for (std::string word; words >> word;) {
    if (word == "{sync}") {
      if (!video) throw Error("camera command: {sync} belongs to a video command");
      if (v.sync != "off") {
        args.push_back("--sync");
        args.push_back(v.sync);
      }
      continue;
    }
    std::string expanded;
    for (std::size_t i = 0; i < word.size();) {
      if (word[i] != '{') {
        expanded.push_back(word[i++]);
        continue;
      }
      const auto close = word.find('}', i);
      const std::string key = word.substr(i, close == std::string::npos ? close : close - i + 1);
      const auto it = std::find_if(std::begin(values), std::end(values),
                                   [&](const auto& entry) { return key == entry.first; });
      if (it == std::end(values))
        throw Error(
            fmt::format("camera command: unknown placeholder '{}' in '{}'", key, command_template));
      expanded += it->second;
      i += key.size();
    }
    args.push_back(expanded);
  }
  if (args.empty()) throw Error("camera command: empty");
  return args;
}

std::unique_ptr<CameraBackend> MakeRpicamCamera(const RpicamOptions& options) {
  return std::make_unique<RpicamCamera>(options);
}

}  // namespace lfcam
