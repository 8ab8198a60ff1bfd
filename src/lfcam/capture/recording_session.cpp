#include "lfcam/capture/recording_session.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "lfcam/capture/array_status.h"
#include "lfcam/capture/concurrency.h"
#include "lfcam/capture/manifest_keeper.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"

namespace lfcam {

namespace {

namespace fs = std::filesystem;

// A node unreachable this many polls in a row (half a second apart) once the recording has
// ended is left for `fetch`.
constexpr int kUnreachablePolls = 6;

std::string StreamFileName(int row, int col) {
  return fmt::format("cam_{:02d}_{:02d}.mjpeg", row, col);
}

void SleepUntilHostNs(std::int64_t t) {
  const std::int64_t wait = t - HostClockUnixNs();
  if (wait > 0) std::this_thread::sleep_for(std::chrono::nanoseconds(wait));
}

void RequireOptions(const RecordOptions& o) {
  if (!(o.fps > 0 && o.fps <= 1000)) throw Error(fmt::format("fps {} is not in (0, 1000]", o.fps));
  if (!(o.seconds > 0 && o.seconds <= 3600))
    throw Error(fmt::format("a recording of {} s is not in (0, 3600]", o.seconds));
  if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
    throw Error(fmt::format("a video mode of {}x{} is out of range", o.width, o.height));
  if (o.stagger < 1 || o.stagger > 64)
    throw Error(fmt::format("--stagger {} is not 1..64 groups", o.stagger));
}

}  // namespace

NodeRecording AskRecording(NodeClient& client, const std::string& id, bool with_frames) {
  const std::string where = fmt::format("{}: recording '{}'", client.address(), id);
  const TimedReply reply =
      client.Get("/v1/recordings/" + id + (with_frames ? std::string() : "?frames=0"));
  const nlohmann::json& body = reply.body;
  const nlohmann::json& record = JsonField(body, "record", where);
  const nlohmann::json& video = JsonField(record, "video", where);
  NodeRecording r;
  r.status = JsonString(video, "status", where);
  if (video.contains("reason")) r.reason = JsonString(video, "reason", where);
  r.frame_count = JsonInteger(body, "frame_count", 0, INT64_MAX, where);
  if (r.status == "recording") return r;
  r.size = JsonUnsigned(record, "size", UINT64_MAX, where);
  r.sha256 = JsonString(record, "sha256", where);
  if (!with_frames) return r;
  const nlohmann::json& entries = JsonField(body, "frames", where);
  if (!entries.is_array()) throw Error(where + ": frames must be an array");
  nlohmann::json rows = nlohmann::json::array();
  for (const nlohmann::json& e : entries)
    rows.push_back({JsonInteger(e, "sequence", 0, INT64_MAX, where),
                    JsonUnsigned(e, "offset", UINT64_MAX / 2, where),
                    JsonUnsigned(e, "size", UINT64_MAX / 2, where),
                    JsonInteger(e, "wall_clock_ns", 0, INT64_MAX, where),
                    JsonInteger(e, "sensor_ns", 0, INT64_MAX, where)});
  r.frames = FramesFromJson(rows, where);
  if (!r.frames.empty() && r.frames.back().offset + r.frames.back().size != r.size)
    throw Error(fmt::format("{}: the frames end at byte {}, the stream at {}", where,
                            r.frames.back().offset + r.frames.back().size, r.size));
  if (std::int64_t(r.frames.size()) != r.frame_count)
    throw Error(
        fmt::format("{}: {} frames listed, {} counted", where, r.frames.size(), r.frame_count));
  return r;
}

void ApplyRecording(ShotImage& image, const NodeRecording& r) {
  image.frames = r.frames;
  image.capture["recording"] = r.status;
  if (r.status == "recording") return;
  image.capture["size"] = r.size;
  image.capture["sha256"] = r.sha256;
  image.capture["frames"] = r.frames.size();
  if (!r.frames.empty()) image.capture["trigger_unix_ns"] = r.frames.front().wall_clock_ns;
  if (r.reason.empty())
    image.capture.erase("node_reason");
  else
    image.capture["node_reason"] = r.reason;
}

SessionReport RecordSession(const ArrayConfig& array, const SharedKey& key, const fs::path& session,
                            const RecordOptions& options) {
  RequireOptions(options);
  CaptureManifest manifest = OpenSessionManifest(array, session);
  const std::string session_id = manifest.source["session_id"];
  const std::string shot_name = NextShotName(manifest, ShotKind::kVideo);
  const std::string folder = ShotFolder(ShotKind::kVideo, shot_name);
  const std::string id = fmt::format("{}-{}", session_id, shot_name);

  SessionReport report;
  report.shot = shot_name;
  report.cameras = int(array.nodes.size());

  // Who is ready, how far away, and which ready node leads the sync (the first in the grid).
  const std::vector<NodeReport> status = ArrayStatus(array, key);
  double slowest_ms = 0;
  std::optional<std::size_t> server;
  for (std::size_t i = 0; i < status.size(); ++i) {
    slowest_ms = std::max(slowest_ms, status[i].round_trip_ms);
    if (options.sync && status[i].ready() &&
        (!server || std::pair(array.nodes[i].row, array.nodes[i].col) <
                        std::pair(array.nodes[*server].row, array.nodes[*server].col)))
      server = i;
  }
  const double margin_s = std::max(options.margin_s, 3 * slowest_ms / 1000.0);
  const auto start_clock = std::chrono::steady_clock::now();
  const std::int64_t t0 = HostClockUnixNs() + std::int64_t(margin_s * 1e9);
  const std::int64_t end = t0 + std::int64_t(options.seconds * 1e9);

  const int groups = options.stagger;
  const double stagger_step_ns = 1e9 / (options.fps * groups);
  std::vector<ShotImage> images(array.nodes.size());
  RunConcurrently(array.nodes.size(), kMaxRequestThreads, [&](std::size_t i) {
    const ArrayNode& n = array.nodes[i];
    const std::string role = !options.sync ? "off" : i == server ? "server" : "client";
    const int group = NodeGroup(array, n, groups);
    const auto stagger_ns = std::int64_t(std::llround(group * stagger_step_ns));
    ShotImage& image = images[i];
    image.row = n.row;
    image.col = n.col;
    image.file = folder + "/" + StreamFileName(n.row, n.col);
    image.capture = {{"node", n.address}, {"capture_id", id}, {"requested_unix_ns", t0},
                     {"sync", role},      {"group", group},   {"stagger_ns", stagger_ns}};
    if (!status[i].ready()) {
      image.status = ImageStatus::kMissing;
      image.capture["reason"] =
          fmt::format("not ready at the start: {}", fmt::join(status[i].problems, "; "));
      return;
    }
    try {
      NodeClient client(n.address, key, {2.0, 10.0});
      client.Post("/v1/record", {{"id", id},
                                 {"shot", shot_name},
                                 {"at_unix_ns", t0},
                                 {"video",
                                  {{"fps", options.fps},
                                   {"seconds", options.seconds},
                                   {"width", options.width},
                                   {"height", options.height},
                                   {"sync", role},
                                   {"stagger_ns", stagger_ns}}},
                                 {"settings", SettingsToJson(array.settings)},
                                 {"max_clock_offset_ms", array.max_clock_offset_ms}});
      image.status = ImageStatus::kCaptured;
      image.capture["recording"] = "recording";
    } catch (const Error& e) {
      image.status = ImageStatus::kMissing;
      image.capture["reason"] = e.what();
    }
  });
  AddCamerasWithoutNodes(
      array, [&](int r, int c) { return folder + "/" + StreamFileName(r, c); }, images);
  Shot shot{ShotKind::kVideo, shot_name, {}, images};
  shot.video = VideoShot{
      options.fps, options.seconds, options.width, options.height, options.sync ? "on" : "off",
      t0,          groups};
  manifest.shots.push_back(std::move(shot));
  ManifestKeeper keeper(session, manifest);
  keeper.Flush();

  // Until every started node has finished (or gone quiet, or the time is up): its frame count
  // for the progress meanwhile, then its frames.
  std::vector<std::size_t> waiting;
  for (std::size_t i = 0; i < images.size(); ++i)
    if (images[i].status == ImageStatus::kCaptured) waiting.push_back(i);
  report.fired = int(waiting.size());
  std::vector<std::int64_t> counted(images.size(), 0);
  std::vector<int> silent(images.size(), 0);
  std::vector<std::string> last_error(images.size());
  // The nodes still recording stop being waited for once the recording has ended and none of
  // them has delivered a new frame for finish_timeout_s: a real node finishes within a frame or
  // two of the end; simulated ones render their frames slower than real time, sharing the
  // host's cores, and are waited for as long as the array makes progress.
  const auto stall = std::int64_t(options.finish_timeout_s * 1e9);
  std::atomic<std::int64_t> progressed{end};
  auto update = [&](const ShotImage& image, auto&& change) {
    keeper.Update([&](CaptureManifest& m) {
      for (ShotImage& p : m.shots.back().pending)
        if (p.row == image.row && p.col == image.col) change(p);
    });
  };
  SleepUntilHostNs(t0);
  while (!waiting.empty()) {
    std::vector<char> finished(waiting.size(), 0);
    RunConcurrently(waiting.size(), kMaxRequestThreads, [&](std::size_t w) {
      const std::size_t i = waiting[w];
      const ShotImage& image = images[i];
      try {
        NodeClient client(image.capture["node"].get<std::string>(), key, {2.0, 10.0});
        NodeRecording r = AskRecording(client, id, false);
        silent[i] = 0;
        if (r.status != "recording") r = AskRecording(client, id, true);
        if (r.frame_count > counted[i]) {
          if (options.progress) options.progress(r.frame_count - counted[i]);
          const std::int64_t now = HostClockUnixNs();
          for (std::int64_t seen = progressed; seen < now;)
            if (progressed.compare_exchange_weak(seen, now)) break;
        }
        counted[i] = r.frame_count;
        if (r.status == "recording") {
          if (HostClockUnixNs() - progressed > stall) {
            update(image, [&](ShotImage& p) {
              p.capture["reason"] = fmt::format(
                  "still recording, no new frame from any node for {:.0f} s after the "
                  "recording's end (`lfcam capture fetch` asks again)",
                  options.finish_timeout_s);
            });
            finished[w] = 1;
          }
          return;
        }
        update(image, [&](ShotImage& p) {
          ApplyRecording(p, r);
          if (r.status == "failed") {
            p.status = ImageStatus::kMissing;
            p.capture["reason"] = "the node recorded nothing: " + r.reason;
          }
        });
        finished[w] = 1;
      } catch (const Error& e) {
        last_error[i] = e.what();
        if (HostClockUnixNs() > end && ++silent[i] >= kUnreachablePolls) {
          update(image, [&](ShotImage& p) {
            p.capture["reason"] = fmt::format(
                "{} (when the recording ended; `lfcam capture fetch` completes it once the "
                "node is back)",
                last_error[i]);
          });
          finished[w] = 1;
        }
      }
    });
    std::vector<std::size_t> still;
    for (std::size_t w = 0; w < waiting.size(); ++w)
      if (!finished[w]) still.push_back(waiting[w]);
    waiting = std::move(still);
    if (!waiting.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  keeper.Flush();
  report.capture_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
  report.trigger_wait_s = margin_s;
  CollectProblems(keeper.Snapshot(), report);
  if (!options.fetch) return report;

  const SessionReport fetched = FetchSession(array, key, session, options.fetch_options);
  report.fetch_s = fetched.fetch_s;
  report.bytes = fetched.bytes;
  report.images_ok = fetched.images_ok;
  report.problems = fetched.problems;
  return report;
}

}  // namespace lfcam
