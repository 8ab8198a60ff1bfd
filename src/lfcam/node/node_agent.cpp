#include "lfcam/node/node_agent.h"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <time.h>

#include <atomic>
#include <fstream>
#include <future>
#include <mutex>
#include <thread>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/node/capture_store.h"
#include "lfcam/node/recording.h"
#include "lfcam/node/system_status.h"

// After Eigen (through json_input.h): <resolv.h>, which httplib includes, defines a macro _res.
#include <httplib.h>

namespace lfcam {

std::int64_t NodeClockUnixNs(std::int64_t simulated_offset_ns) {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec + simulated_offset_ns;
}

namespace {

namespace fs = std::filesystem;
constexpr const char* kSettingsFile = ".settings.json";

// Sleeps until the node's clock reads `t` (absolute, so a late wake-up is not made later).
void SleepUntilUnixNs(std::int64_t t, std::int64_t offset_ns) {
  const std::int64_t system_t = t - offset_ns;
  timespec ts{system_t / 1'000'000'000, long(system_t % 1'000'000'000)};
  while (::clock_nanosleep(CLOCK_REALTIME, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

// A refusal the host can act on: an HTTP status, a reason keyword and a message.
struct Refusal {
  int status;
  std::string reason, message;
};

void Reply(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(body.dump() + "\n", "application/json");
}

void Refuse(httplib::Response& res, const Refusal& r) {
  Reply(res, r.status, {{"error", r.message}, {"reason", r.reason}});
}

}  // namespace

struct NodeAgent::Impl {
  NodeOptions options;
  std::unique_ptr<CameraBackend> camera;
  CaptureStore store;
  RequestVerifier verifier;
  httplib::Server server;
  std::mutex camera_mutex;  // one capture or preview at a time
  std::mutex settings_mutex;
  CaptureSettings settings;
  bool configured = false;
  std::mutex log_mutex;
  // The recording under way, if any (one at a time).
  struct ActiveRecording {
    std::string id;
    std::atomic<bool> stop{false}, done{false};
    std::thread thread;
  };
  std::mutex recording_mutex;
  std::unique_ptr<ActiveRecording> recording;

  Impl(NodeOptions o, std::unique_ptr<CameraBackend> c)
      : options(std::move(o)),
        camera(std::move(c)),
        store(options.captures),
        verifier(options.key, options.signature_window) {
    LoadSettings();
    server.new_task_queue = [n = options.threads] { return new httplib::ThreadPool(n); };
    server.set_payload_max_length(kMaxRequestBodyBytes);
    server.set_read_timeout(10, 0);
    server.set_write_timeout(30, 0);
    server.set_keep_alive_max_count(1000);
    server.set_tcp_nodelay(true);
    Route();
  }

  std::int64_t Now() const { return NodeClockUnixNs(options.simulated_clock_offset_ns); }

  template <typename... Args>
  void Log(fmt::format_string<Args...> format, Args&&... args) {
    std::lock_guard lock(log_mutex);
    const auto now = std::chrono::system_clock::now();
    fmt::print(stderr, "{:%H:%M:%S} lfcam-node {}: {}\n",
               std::chrono::floor<std::chrono::milliseconds>(now), options.name,
               fmt::format(format, std::forward<Args>(args)...));
  }

  void LoadSettings() {
    const fs::path path = options.captures / kSettingsFile;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return;
    try {
      const auto bytes = ReadFileBytes(path, 1 << 16, "settings");
      settings = SettingsFromJson(
          ParseJsonBounded({reinterpret_cast<const char*>(bytes.data()), bytes.size()},
                           path.string()),
          path.string());
      camera->Configure(settings);
      configured = true;
    } catch (const Error& e) {
      Log("ignoring the saved settings: {}", e.what());
    }
  }

  void ApplySettings(const CaptureSettings& s) {
    std::scoped_lock lock(camera_mutex, settings_mutex);
    camera->Configure(s);
    settings = s;
    configured = true;
    const std::string text = SettingsToJson(s).dump(2) + "\n";
    WriteFileAtomically(options.captures / kSettingsFile,
                        {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
  }

  std::optional<ClockOffset> ClockStatus(std::chrono::steady_clock::duration max_age) const {
    if (options.simulated_clock_offset_ns != 0)
      return ClockOffset{double(options.simulated_clock_offset_ns) / 1e6,
                         "simulated (--simulate-clock-offset-ms)"};
    return ChronyClockOffset(max_age);
  }

  nlohmann::json Status() {
    SystemStatus system = ReadSystemStatus(options.captures);
    system.clock = ClockStatus(kStatusClockMaxAge);
    CameraProbe probe;
    {
      std::unique_lock lock(camera_mutex, std::try_to_lock);
      probe = lock.owns_lock()
                  ? camera->Probe()
                  : CameraProbe{true, camera->name(),
                                RecordingStatus().is_string() ? "recording" : "capturing"};
    }
    std::lock_guard lock(settings_mutex);
    return {
        {"agent", "lfcam-node"},
        {"version", kNodeAgentVersion},
        {"lfcam_version", LFCAM_VERSION},
        {"name", options.name},
        {"backend", camera->name()},
        {"camera", {{"present", probe.present}, {"model", probe.model}, {"detail", probe.detail}}},
        {"configured", configured},
        {"sensor_mode", configured ? fmt::format("{}x{}", settings.width, settings.height) : ""},
        {"settings", configured ? SettingsToJson(settings) : nlohmann::json()},
        {"system", SystemStatusToJson(system)},
        {"captures_held", store.count()},
        {"recording", RecordingStatus()},
        {"max_clock_offset_ms", options.max_clock_offset_ms},
        {"min_free_bytes", options.min_free_bytes},
        {"node_time_unix_ns", Now()}};
  }

  nlohmann::json RecordingStatus() {
    std::lock_guard lock(recording_mutex);
    if (!recording || recording->done) return nullptr;
    return recording->id;
  }

  // Stops the recording under way (what it recorded is kept, "truncated"), or joins one that
  // ended.
  void StopRecording() {
    std::unique_ptr<ActiveRecording> r;
    {
      std::lock_guard lock(recording_mutex);
      r = std::move(recording);
    }
    if (!r) return;
    r->stop = true;
    if (r->thread.joinable()) r->thread.join();
  }

  // Why this node must not capture now, or nullopt.
  std::optional<Refusal> CaptureRefusal(const CaptureSettings& array_settings,
                                        double max_offset_ms) {
    {
      std::lock_guard lock(settings_mutex);
      if (!configured)
        return Refusal{409, "settings", "the camera is not configured (lfcam capture configure)"};
      const auto diffs = SettingsDifferences(settings, array_settings);
      if (!diffs.empty())
        return Refusal{409, "settings",
                       fmt::format("settings differ from the array's: {}", fmt::join(diffs, ", "))};
    }
    if (const auto clock = ClockStatus(kCaptureClockMaxAge);
        clock && std::abs(clock->offset_ms) > max_offset_ms)
      return Refusal{409, "clock",
                     fmt::format("clock offset {:.1f} ms ({}) exceeds {:.1f} ms", clock->offset_ms,
                                 clock->source, max_offset_ms)};
    if (const auto free = store.FreeBytes(); free < options.min_free_bytes)
      return Refusal{507, "disk",
                     fmt::format("disk nearly full: {:.0f} MB free, {} MB needed",
                                 double(free) / 1e6, options.min_free_bytes / 1000000)};
    return std::nullopt;
  }

  void Capture(const httplib::Request& req, httplib::Response& res) {
    const auto body = ParseJsonBounded(req.body, "capture request");
    ShotRequest shot{JsonString(body, "id", "capture request"),
                     JsonString(body, "kind", "capture request"),
                     JsonString(body, "shot", "capture request")};
    if (!IsValidCaptureId(shot.id) || !IsValidCaptureId(shot.shot) || !IsValidCaptureId(shot.kind))
      return Refuse(res, {400, "request", "id, kind and shot must be 1..64 of [A-Za-z0-9_.-]"});
    const std::int64_t at = JsonInteger(body, "at_unix_ns", 0, INT64_MAX, "capture request");
    const CaptureSettings array_settings = SettingsFromJson(
        JsonField(body, "settings", "capture request"), "capture request: settings");
    double max_offset_ms = options.max_clock_offset_ms;
    if (body.contains("max_clock_offset_ms"))
      max_offset_ms =
          std::min(max_offset_ms, JsonNumber(body, "max_clock_offset_ms", "capture request"));

    if (RecordingStatus().is_string()) return Refuse(res, {409, "busy", "the camera is recording"});
    if (const auto held = store.Find(shot.id)) {
      if (held->requested_unix_ns == at) return Reply(res, 200, RecordToJson(*held));
      return Refuse(res,
                    {409, "exists", fmt::format("capture '{}' exists (another time)", shot.id)});
    }
    const std::int64_t lead = at - Now();
    if (lead < 0)
      return Refuse(res,
                    {409, "late", fmt::format("the trigger time is {:.1f} ms past", -lead / 1e6)});
    if (lead > std::int64_t(120) * 1'000'000'000)
      return Refuse(res, {400, "request", "the trigger time is more than 120 s ahead"});
    if (auto refusal = CaptureRefusal(array_settings, max_offset_ms)) {
      Log("refusing capture '{}': {}", shot.id, refusal->message);
      return Refuse(res, *refusal);
    }

    std::lock_guard camera_lock(camera_mutex);
    camera->Prepare(shot);
    if (const std::int64_t late = Now() - at; late > 0) {
      Log("missed capture '{}' by {:.1f} ms", shot.id, late / 1e6);
      return Refuse(res, {409, "late",
                          fmt::format("preparing the camera took until {:.1f} ms after the trigger "
                                      "time",
                                      late / 1e6)});
    }
    CaptureRecord record;
    record.id = shot.id;
    record.kind = shot.kind;
    record.shot = shot.shot;
    record.requested_unix_ns = at;
    {
      std::lock_guard lock(settings_mutex);
      record.settings = SettingsToJson(settings);
    }
    // Everything after the trigger (collecting, hashing, writing the image) runs on a thread of
    // the lowest priority that sleeps until 20 ms after T: at T itself this thread only wakes,
    // reads the clock and fires, and waking nothing else it costs one context switch. A node
    // that shares its machine with other nodes (the tests, the benchmark: 100 on two cores) or
    // with the camera's own pipeline then does not hold up their triggers (docs/benchmarks.md).
    std::promise<void> fired_promise;
    std::exception_ptr failure;
    std::thread after_trigger([&, fired = fired_promise.get_future()]() mutable {
      sched_param lowest{};
      ::pthread_setschedparam(::pthread_self(), SCHED_IDLE, &lowest);
      SleepUntilUnixNs(at + 20'000'000, options.simulated_clock_offset_ns);
      fired.wait();
      if (failure) return;  // the camera did not fire
      try {
        record = store.Save(std::move(record), camera->Collect(std::chrono::seconds(30)));
      } catch (...) {
        failure = std::current_exception();
      }
    });
    ::prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);  // wake on the nanosecond asked, not 50 us later
    SleepUntilUnixNs(at, options.simulated_clock_offset_ns);
    record.trigger_unix_ns = Now();
    try {
      camera->Fire();
    } catch (...) {
      failure = std::current_exception();
    }
    fired_promise.set_value();
    after_trigger.join();
    if (failure) std::rethrow_exception(failure);
    const std::int64_t fired = record.trigger_unix_ns;
    if (!options.quiet)
      Log("captured '{}' {:+.3f} ms from T, {} bytes", shot.id, (fired - at) / 1e6, record.size);
    Reply(res, 200, RecordToJson(record));
  }

  // POST /v1/record: checks what the host asks, answers at once (202) and records on a thread
  // of its own from the start time; GET /v1/recordings/ID says how it goes.
  void Record(const httplib::Request& req, httplib::Response& res) {
    const auto body = ParseJsonBounded(req.body, "record request");
    RecordRequest request;
    request.id = JsonString(body, "id", "record request");
    request.shot = JsonString(body, "shot", "record request");
    if (!IsValidCaptureId(request.id) || !IsValidCaptureId(request.shot))
      return Refuse(res, {400, "request", "id and shot must be 1..64 of [A-Za-z0-9_.-]"});
    request.start_unix_ns = JsonInteger(body, "at_unix_ns", 0, INT64_MAX, "record request");
    nlohmann::json video = JsonField(body, "video", "record request");
    video["status"] = "recording";
    video["frames"] = 0;
    request.video = VideoInfoFromJson(video, "record request: video");
    const CaptureSettings array_settings =
        SettingsFromJson(JsonField(body, "settings", "record request"), "record request: settings");
    double max_offset_ms = options.max_clock_offset_ms;
    if (body.contains("max_clock_offset_ms"))
      max_offset_ms =
          std::min(max_offset_ms, JsonNumber(body, "max_clock_offset_ms", "record request"));

    if (const auto held = store.Find(request.id)) {
      if (held->video && held->requested_unix_ns == request.start_unix_ns)
        return Reply(res, 202, RecordToJson(*held));
      return Refuse(res,
                    {409, "exists", fmt::format("capture '{}' exists (another time)", request.id)});
    }
    const std::int64_t lead = request.start_unix_ns - Now();
    if (lead < 0)
      return Refuse(res,
                    {409, "late", fmt::format("the start time is {:.1f} ms past", -lead / 1e6)});
    if (lead > std::int64_t(120) * 1'000'000'000)
      return Refuse(res, {400, "request", "the start time is more than 120 s ahead"});
    if (const auto needed = camera->RecordLead(request.video); lead < needed.count() * 1'000'000)
      return Refuse(
          res, {409, "late",
                fmt::format("the camera needs {:.1f} s to start recording{}, the start "
                            "is {:.1f} s away (lfcam capture record --margin)",
                            double(needed.count()) / 1e3,
                            request.video.sync == "off" ? "" : " in sync", double(lead) / 1e9)});
    if (double(array_settings.exposure_us) > 1e6 / request.video.fps)
      return Refuse(res, {409, "settings",
                          fmt::format("an exposure of {} us is longer than a frame at {} fps",
                                      array_settings.exposure_us, request.video.fps)});
    if (auto refusal = CaptureRefusal(array_settings, max_offset_ms)) {
      Log("refusing recording '{}': {}", request.id, refusal->message);
      return Refuse(res, *refusal);
    }
    // About a quarter of a byte a pixel at the JPEG qualities used (measured on the simulator
    // at 95: 0.2-0.3).
    const double expected = 0.3 * request.video.width * request.video.height * request.video.fps *
                            request.video.seconds;
    if (const auto free = store.FreeBytes();
        double(free) < expected + double(options.min_free_bytes))
      return Refuse(res, {507, "disk",
                          fmt::format("not enough disk for the recording: {:.0f} MB free, about "
                                      "{:.0f} MB needed",
                                      double(free) / 1e6,
                                      (expected + double(options.min_free_bytes)) / 1e6)});

    std::lock_guard lock(recording_mutex);
    if (recording && !recording->done)
      return Refuse(res, {409, "busy", fmt::format("recording '{}' is under way", recording->id)});
    if (recording && recording->thread.joinable()) recording->thread.join();
    CaptureRecord record;
    record.id = request.id;
    record.kind = "video";
    record.shot = request.shot;
    record.requested_unix_ns = request.start_unix_ns;
    {
      std::lock_guard settings_lock(settings_mutex);
      record.settings = SettingsToJson(settings);
    }
    record.video = request.video;
    std::shared_ptr<CaptureStore::Recording> writer = store.BeginRecording(record);
    recording = std::make_unique<ActiveRecording>();
    recording->id = request.id;
    ActiveRecording* active = recording.get();
    active->thread = std::thread([this, active, writer, request] {
      std::string status = "complete", reason;
      try {
        std::lock_guard camera_lock(camera_mutex);
        camera->Record(
            request,
            [&](CapturedFrame&& f) {
              writer->Append({f.sequence, 0, 0, f.wall_clock_ns, f.sensor_ns}, f.jpeg);
            },
            active->stop);
        if (active->stop) status = "truncated", reason = "the node was stopped mid-recording";
      } catch (const Error& e) {
        status = "truncated";
        reason = e.what();
      }
      if (writer->frames() == 0 && status != "complete") status = "failed";
      try {
        const CaptureRecord done = writer->Finish(status, reason);
        if (!options.quiet || status != "complete")
          Log("recording '{}' {}: {} frames, {} bytes{}", done.id, status, done.video->frames,
              done.size, reason.empty() ? "" : " (" + reason + ")");
      } catch (const Error& e) {
        Log("recording '{}': {}", request.id, e.what());
      }
      active->done = true;
    });
    Log("recording '{}' from {:.3f} s ahead: {:g} s at {:g} fps, {}x{}, sync {}", request.id,
        lead / 1e9, request.video.seconds, request.video.fps, request.video.width,
        request.video.height, request.video.sync);
    Reply(res, 202, RecordToJson(record));
  }

  void RecordingInfo(const httplib::Request& req, httplib::Response& res) {
    const std::string id = req.matches[1];
    const auto record = store.Find(id);
    if (!record || !record->video)
      return Refuse(res, {404, "missing", fmt::format("no recording '{}'", id)});
    const std::vector<VideoFrameEntry> entries = store.Frames(*record);
    nlohmann::json reply = {{"record", RecordToJson(*record)}, {"frame_count", entries.size()}};
    // ?frames=0: the count alone (the host's progress while the array records).
    if (req.get_param_value("frames") != "0") {
      nlohmann::json frames = nlohmann::json::array();
      for (const VideoFrameEntry& f : entries) frames.push_back(FrameEntryToJson(f));
      reply["frames"] = std::move(frames);
    }
    Reply(res, 200, reply);
  }

  void Download(const httplib::Request& req, httplib::Response& res) {
    const std::string id = req.matches[1];
    const auto record = store.Find(id);
    if (!record) return Refuse(res, {404, "missing", fmt::format("no capture '{}'", id)});
    if (record->video && record->video->status == "recording")
      return Refuse(res, {409, "recording", fmt::format("'{}' is still recording", id)});
    auto file = std::make_shared<std::ifstream>(store.DataPath(*record), std::ios::binary);
    if (!*file) return Refuse(res, {500, "io", fmt::format("cannot open capture '{}'", id)});
    res.set_header("X-Lfcam-Sha256", record->sha256);
    const NodeFaults faults = options.faults;
    const std::uint64_t size = record->size;
    const auto start = std::chrono::steady_clock::now();
    res.set_content_provider(
        std::size_t(size), "image/jpeg",
        [file, faults, size, start](std::size_t offset, std::size_t length,
                                    httplib::DataSink& sink) {
          std::vector<char> buffer(std::min<std::size_t>(length, 64 * 1024));
          file->clear();
          file->seekg(std::streamoff(offset));
          file->read(buffer.data(), std::streamsize(buffer.size()));
          const std::size_t got = std::size_t(file->gcount());
          if (got == 0) return false;
          if (faults.corrupt_downloads && offset <= size / 2 && size / 2 < offset + got)
            buffer[size / 2 - offset] ^= 0x5A;
          if (faults.download_bytes_per_s > 0) {
            const auto due = start + std::chrono::duration<double>(double(offset + got) /
                                                                   faults.download_bytes_per_s);
            std::this_thread::sleep_until(
                std::chrono::time_point_cast<std::chrono::steady_clock::duration>(due));
          }
          return sink.write(buffer.data(), got);
        });
  }

  void Identify(const httplib::Request& req, httplib::Response& res) {
    int seconds = 10;
    if (!req.body.empty()) {
      const auto body = ParseJsonBounded(req.body, "identify request");
      if (body.contains("seconds"))
        seconds = int(JsonInteger(body, "seconds", 1, 600, "identify request"));
    }
    for (int i = 0; i < 3; ++i)
      Log("*** IDENTIFY *** this is node {} ({}): look for the blinking activity LED", options.name,
          camera->name());
    const bool led = BlinkActivityLed(seconds);
    Reply(res, 200, {{"name", options.name}, {"led", led}, {"seconds", seconds}});
  }

  // Sets the activity LED's trigger to "timer" for `seconds`, then back (needs write access to
  // /sys/class/leds/ACT, as the systemd unit gives). Returns whether it could.
  static bool BlinkActivityLed(int seconds) {
    for (const char* led : {"/sys/class/leds/ACT", "/sys/class/leds/led0"}) {
      const fs::path trigger = fs::path(led) / "trigger";
      std::ifstream in(trigger);
      std::string all, previous;
      if (!std::getline(in, all)) continue;
      // The current trigger is the one in brackets.
      const auto open = all.find('['), close = all.find(']');
      if (open != std::string::npos && close > open)
        previous = all.substr(open + 1, close - open - 1);
      std::ofstream out(trigger);
      if (!(out << "timer" << std::flush)) continue;
      std::thread([trigger, previous, seconds] {
        std::this_thread::sleep_for(std::chrono::seconds(seconds));
        std::ofstream(trigger) << (previous.empty() ? "mmc0" : previous);
      }).detach();
      return true;
    }
    return false;
  }

  using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;

  // Every route: the signature first, then the handler; lfcam errors become 400 with the
  // message, anything else 500.
  httplib::Server::Handler Signed(Handler handler) {
    return [this, handler](const httplib::Request& req, httplib::Response& res) {
      const auto refusal =
          verifier.Verify(req.method, req.target, req.get_header_value(kTimestampHeader),
                          req.get_header_value(kNonceHeader),
                          req.get_header_value(kSignatureHeader), req.body, Now() / 1'000'000);
      if (refusal) {
        Log("refused {} {} from {}: {}", req.method, req.path, req.remote_addr, *refusal);
        return Refuse(res, {401, "unauthorized", *refusal});
      }
      try {
        handler(req, res);
      } catch (const Error& e) {
        Log("{} {}: {}", req.method, req.path, e.what());
        Refuse(res, {400, "error", e.what()});
      } catch (const std::exception& e) {
        Log("{} {}: internal error: {}", req.method, req.path, e.what());
        Refuse(res, {500, "internal", e.what()});
      }
    };
  }

  void Route() {
    server.Get("/v1/status", Signed([this](const auto&, auto& res) { Reply(res, 200, Status()); }));
    server.Post("/v1/configure", Signed([this](const auto& req, auto& res) {
                  CaptureSettings base;
                  {
                    std::lock_guard lock(settings_mutex);
                    base = settings;
                  }
                  const CaptureSettings s = SettingsFromJson(
                      ParseJsonBounded(req.body, "configure request"), "configure request", base);
                  ApplySettings(s);
                  Log("configured: {}", SettingsToJson(s).dump());
                  Reply(res, 200, SettingsToJson(s));
                }));
    server.Post("/v1/capture", Signed([this](const auto& req, auto& res) { Capture(req, res); }));
    server.Get("/v1/captures", Signed([this](const auto&, auto& res) {
                 nlohmann::json list = nlohmann::json::array();
                 for (const CaptureRecord& r : store.List()) list.push_back(RecordToJson(r));
                 Reply(res, 200, {{"captures", list}});
               }));
    const std::string one = R"(/v1/captures/([A-Za-z0-9_.\-]{1,64}))";
    server.Get(one, Signed([this](const auto& req, auto& res) { Download(req, res); }));
    server.Delete(one, Signed([this](const auto& req, auto& res) {
                    const std::string id = req.matches[1];
                    if (!store.Remove(id))
                      return Refuse(res, {404, "missing", fmt::format("no capture '{}'", id)});
                    Reply(res, 200, {{"deleted", id}});
                  }));
    server.Post("/v1/record", Signed([this](const auto& req, auto& res) { Record(req, res); }));
    server.Get(R"(/v1/recordings/([A-Za-z0-9_.\-]{1,64}))",
               Signed([this](const auto& req, auto& res) { RecordingInfo(req, res); }));
    server.Post("/v1/identify", Signed([this](const auto& req, auto& res) { Identify(req, res); }));
    server.Get("/v1/preview", Signed([this](const auto& req, auto& res) {
                 int width = 320;
                 if (req.has_param("width")) {
                   const std::string w = req.get_param_value("width");
                   width = std::clamp(std::atoi(w.c_str()), 16, 1024);
                 }
                 if (RecordingStatus().is_string())
                   return Refuse(res, {409, "busy", "the camera is recording"});
                 std::string jpeg;
                 {
                   std::lock_guard lock(camera_mutex);
                   jpeg = camera->Preview(width);
                 }
                 res.set_content(jpeg, "image/jpeg");
               }));
    if (!options.quiet)
      server.set_logger([this](const httplib::Request& req, const httplib::Response& res) {
        if (req.path != "/v1/status") Log("{} {} -> {}", req.method, req.path, res.status);
      });
  }
};

NodeAgent::NodeAgent(NodeOptions options, std::unique_ptr<CameraBackend> camera)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(camera))) {}

NodeAgent::~NodeAgent() { Stop(); }

int NodeAgent::Bind(const std::string& host, int port) {
  if (port == 0) {
    const int bound = impl_->server.bind_to_any_port(host);
    if (bound <= 0) throw Error(fmt::format("cannot listen on {}: no free port", host));
    return bound;
  }
  if (!impl_->server.bind_to_port(host, port))
    throw Error(
        fmt::format("cannot listen on {}:{} (in use, or not this machine's address?)", host, port));
  return port;
}

void NodeAgent::Serve() { impl_->server.listen_after_bind(); }

void NodeAgent::Stop() {
  if (!impl_) return;
  impl_->server.stop();
  impl_->StopRecording();
}

}  // namespace lfcam
