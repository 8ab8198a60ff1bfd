#include "lfcam/capture/capture_session.h"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <chrono>
#include <mutex>
#include <thread>

#include "lfcam/capture/array_status.h"
#include "lfcam/capture/concurrency.h"
#include "lfcam/capture/manifest_keeper.h"
#include "lfcam/capture/node_client.h"
#include "lfcam/capture/recording_session.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"

namespace lfcam {

namespace {

namespace fs = std::filesystem;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

namespace {

CaptureManifest NewManifest(const ArrayConfig& array) {
  CaptureManifest m;
  m.rows = array.rows;
  m.cols = array.cols;
  m.pitch_mm = array.pitch_mm;
  m.sensor_width = array.settings.width;
  m.sensor_height = array.settings.height;
  m.intrinsics_board = array.intrinsics_board;
  m.world_board = array.world_board;
  const auto now = std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now());
  m.source = {{"controller", "lfcam capture"},
              {"session_id", RandomHex(4)},
              {"created", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", now)}};
  return m;
}

}  // namespace

std::string ShotFolder(ShotKind kind, const std::string& name) {
  switch (kind) {
    case ShotKind::kIntrinsics:
      return "calib/intrinsics/" + name;
    case ShotKind::kWorld:
      return "calib/world";
    case ShotKind::kScene:
      return "scene";
    case ShotKind::kVideo:
      return "video/" + name;
  }
  return name;
}

std::string NextShotName(const CaptureManifest& m, ShotKind kind) {
  if (kind == ShotKind::kScene) return "scene";
  if (kind == ShotKind::kWorld) return "world";
  for (int k = 0;; ++k) {
    const std::string name = fmt::format("{}_{:02d}", kind == ShotKind::kVideo ? "rec" : "shot", k);
    if (std::none_of(m.shots.begin(), m.shots.end(), [&](const Shot& s) { return s.name == name; }))
      return name;
  }
}

void CollectProblems(const CaptureManifest& m, SessionReport& report) {
  report.images_ok = 0;
  report.problems.clear();
  for (const Shot& s : m.shots) {
    report.images_ok += int(s.images.size());
    for (const ShotImage& i : s.pending) {
      std::string reason = i.capture.is_object() ? i.capture.value("reason", "") : "";
      if (reason.empty() && i.status == ImageStatus::kCaptured)
        reason = "on the node, not fetched yet";
      report.problems.push_back({i.row, i.col, s.name, ToString(i.status), reason});
    }
  }
}

int NodeGroup(const ArrayConfig& array, const ArrayNode& node, int groups) {
  if (groups <= 1) return 0;
  const bool in_file = std::any_of(array.nodes.begin(), array.nodes.end(),
                                   [](const ArrayNode& n) { return n.group != 0; });
  return in_file ? node.group % groups : (node.row + node.col) % groups;
}

void AddCamerasWithoutNodes(const ArrayConfig& array,
                            const std::function<std::string(int, int)>& file_name,
                            std::vector<ShotImage>& images) {
  for (int r = 0; r < array.rows; ++r)
    for (int c = 0; c < array.cols; ++c)
      if (!array.node_at(r, c))
        images.push_back({r,
                          c,
                          file_name(r, c),
                          ImageStatus::kMissing,
                          {{"reason", "no node in the array file"}}});
  std::sort(images.begin(), images.end(), [](const auto& a, const auto& b) {
    return std::pair(a.row, a.col) < std::pair(b.row, b.col);
  });
}

CaptureManifest OpenSessionManifest(const ArrayConfig& array, const fs::path& session) {
  std::error_code ec;
  fs::create_directories(session, ec);
  if (ec)
    throw Error(fmt::format("{}: cannot create the session: {}", session.string(), ec.message()));
  CaptureManifest manifest =
      fs::is_regular_file(session / kManifestName, ec) ? ReadManifest(session) : NewManifest(array);
  if (manifest.rows != array.rows || manifest.cols != array.cols)
    throw Error(fmt::format("{}: the session's grid is {}x{}, the array's {}x{}", session.string(),
                            manifest.rows, manifest.cols, array.rows, array.cols));
  if (manifest.sensor_width != array.settings.width ||
      manifest.sensor_height != array.settings.height)
    throw Error(
        fmt::format("{}: the session was shot at {}x{}, the array is set to {}x{}; shoot "
                    "into a new session",
                    session.string(), manifest.sensor_width, manifest.sensor_height,
                    array.settings.width, array.settings.height));
  if (!manifest.source.is_object()) manifest.source = nlohmann::json::object();
  if (!manifest.source.contains("session_id") || !manifest.source["session_id"].is_string())
    manifest.source["session_id"] = RandomHex(4);
  return manifest;
}

SessionReport FetchSession(const ArrayConfig& array, const SharedKey& key, const fs::path& session,
                           const FetchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::error_code ec;
  if (!fs::is_regular_file(session / kManifestName, ec))
    throw Error(fmt::format("{}: not a capture session (no {})", session.string(), kManifestName));
  ManifestKeeper keeper(session, ReadManifest(session));
  const CaptureManifest initial = keeper.Snapshot();
  if (initial.rows != array.rows || initial.cols != array.cols)
    throw Error(fmt::format("{}: the session's grid is {}x{}, the array's {}x{}", session.string(),
                            initial.rows, initial.cols, array.rows, array.cols));

  struct Job {
    std::string shot;
    ShotImage image;
    bool video = false;
  };
  std::vector<Job> jobs;
  for (const Shot& s : initial.shots)
    for (const ShotImage& i : s.pending)
      if (i.status == ImageStatus::kCaptured)
        jobs.push_back({s.name, i, s.kind == ShotKind::kVideo});

  // Moves the image of camera (row, col) in `shot` to the session's images, or updates it.
  auto settle = [&](const Job& job, bool ok, const std::string& reason, bool lost) {
    keeper.Update([&](CaptureManifest& m) {
      for (Shot& s : m.shots) {
        if (s.name != job.shot) continue;
        for (auto it = s.pending.begin(); it != s.pending.end(); ++it) {
          if (it->row != job.image.row || it->col != job.image.col) continue;
          if (ok) {
            ShotImage done = *it;
            done.status = ImageStatus::kOk;
            done.capture.erase("reason");
            s.pending.erase(it);
            s.images.push_back(std::move(done));
            std::sort(s.images.begin(), s.images.end(), [](const auto& a, const auto& b) {
              return std::pair(a.row, a.col) < std::pair(b.row, b.col);
            });
          } else {
            it->capture["reason"] = reason;
            if (lost) it->status = ImageStatus::kMissing;
          }
          return;
        }
      }
    });
  };

  SessionReport report;
  report.cameras = int(array.nodes.size());
  std::atomic<std::uint64_t> bytes{0};
  RunConcurrently(jobs.size(), std::size_t(std::max(1, options.concurrency)), [&](std::size_t j) {
    const Job& job = jobs[j];
    const nlohmann::json& c = job.image.capture;
    const ArrayNode* node = array.node_at(job.image.row, job.image.col);
    const std::string address = node ? node->address : c.value("node", "");
    const fs::path destination = session / job.image.file;
    std::string last_error;
    try {
      const std::string id = JsonString(c, "capture_id", "capture");
      NodeClient client(address, key, {2.0, 15.0});
      nlohmann::json capture = c;
      if (job.video && !c.contains("sha256")) {
        // A recording whose end the host did not see: the node says how it ended.
        const NodeRecording r = AskRecording(client, id);
        if (r.status == "recording") {
          settle(job, false, "still recording on the node", false);
          return;
        }
        keeper.Update([&](CaptureManifest& m) {
          for (Shot& s : m.shots)
            if (s.name == job.shot)
              for (ShotImage& p : s.pending)
                if (p.row == job.image.row && p.col == job.image.col) ApplyRecording(p, r);
        });
        if (r.status == "failed") {
          settle(job, false, "the node recorded nothing: " + r.reason, true);
          return;
        }
        capture["size"] = r.size;
        capture["sha256"] = r.sha256;
      }
      const std::uint64_t size = JsonUnsigned(capture, "size", UINT64_MAX, "capture");
      const std::string sha256 = JsonString(capture, "sha256", "capture");
      fs::create_directories(destination.parent_path());
      // Already here (a fetch that stopped between the rename and the manifest's next write).
      std::error_code exists_ec;
      if (fs::is_regular_file(destination, exists_ec) &&
          fs::file_size(destination, exists_ec) == size && Sha256OfFile(destination) == sha256) {
        settle(job, true, "", false);
        if (options.progress) options.progress(std::int64_t(size));
        return;
      }
      for (int attempt = 0; attempt <= options.retries; ++attempt) {
        if (attempt > 0)
          std::this_thread::sleep_for(std::chrono::milliseconds(250 << (attempt - 1)));
        try {
          bytes += client.Download(id, destination, size, sha256);
          settle(job, true, "", false);
          if (options.progress) options.progress(std::int64_t(size));
          return;
        } catch (const NodeError& e) {
          last_error = e.what();
          if (e.reason() == "gone") {
            settle(job, false, last_error, true);
            return;
          }
        }
      }
    } catch (const Error& e) {
      last_error = e.what();
    }
    settle(job, false, last_error, false);
  });
  keeper.Flush();
  report.fetch_s = SecondsSince(start);
  report.bytes = bytes;
  CollectProblems(keeper.Snapshot(), report);
  return report;
}

SessionReport ShootSession(const ArrayConfig& array, const SharedKey& key, const fs::path& session,
                           const ShootOptions& options) {
  CaptureManifest manifest = OpenSessionManifest(array, session);
  const std::string session_id = manifest.source["session_id"];
  const std::string shot_name = NextShotName(manifest, options.kind);
  if (std::any_of(manifest.shots.begin(), manifest.shots.end(),
                  [&](const Shot& s) { return s.name == shot_name; }))
    throw Error(fmt::format("{}: already has a {} shot; shoot into a new session", session.string(),
                            shot_name));
  const std::string folder = ShotFolder(options.kind, shot_name);

  SessionReport report;
  report.shot = shot_name;
  report.cameras = int(array.nodes.size());

  // Who is ready, and how far away.
  const std::vector<NodeReport> status = ArrayStatus(array, key);
  double slowest_ms = 0;
  for (const NodeReport& r : status) slowest_ms = std::max(slowest_ms, r.round_trip_ms);
  const double margin_s = std::max(options.margin_s, 3 * slowest_ms / 1000.0);
  const int groups = std::max(1, options.groups);
  const auto trigger_start = std::chrono::steady_clock::now();
  const std::int64_t t0 = HostClockUnixNs() + std::int64_t(margin_s * 1e9);

  std::vector<ShotImage> images(array.nodes.size());
  RunConcurrently(array.nodes.size(), kMaxRequestThreads, [&](std::size_t i) {
    const ArrayNode& n = array.nodes[i];
    const int group = NodeGroup(array, n, groups);
    const std::int64_t at = t0 + std::int64_t(group * options.group_delay_s * 1e9);
    const std::string id = fmt::format("{}-{}", session_id, shot_name);
    ShotImage& image = images[i];
    image.row = n.row;
    image.col = n.col;
    image.file = folder + "/" + CameraFileName(n.row, n.col);
    image.capture = {
        {"node", n.address}, {"capture_id", id}, {"requested_unix_ns", at}, {"group", group}};
    if (!status[i].ready()) {
      image.status = ImageStatus::kMissing;
      image.capture["reason"] =
          fmt::format("not ready at trigger time: {}", fmt::join(status[i].problems, "; "));
      return;
    }
    try {
      NodeClient client(n.address, key, {2.0, 10.0});
      const double wait_s = double(at - HostClockUnixNs()) / 1e9;
      const TimedReply reply = client.Post("/v1/capture",
                                           {{"id", id},
                                            {"kind", ToString(options.kind)},
                                            {"shot", shot_name},
                                            {"at_unix_ns", at},
                                            {"settings", SettingsToJson(array.settings)},
                                            {"max_clock_offset_ms", array.max_clock_offset_ms}},
                                           std::max(0.0, wait_s) + options.capture_timeout_s);
      const nlohmann::json& r = reply.body;
      image.status = ImageStatus::kCaptured;
      image.capture["trigger_unix_ns"] = JsonInteger(r, "trigger_unix_ns", 0, INT64_MAX, "capture");
      image.capture["settings"] = JsonField(r, "settings", "capture");
      image.capture["size"] = JsonUnsigned(r, "size", UINT64_MAX, "capture");
      image.capture["sha256"] = JsonString(r, "sha256", "capture");
    } catch (const Error& e) {
      image.status = ImageStatus::kMissing;
      image.capture["reason"] = e.what();
    }
  });
  report.capture_s = SecondsSince(trigger_start);
  report.trigger_wait_s = margin_s;

  AddCamerasWithoutNodes(
      array, [&](int r, int c) { return folder + "/" + CameraFileName(r, c); }, images);

  // Skew: within each group, the latest minus the earliest actual trigger time.
  for (int g = 0; g < groups; ++g) {
    std::int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (const ShotImage& image : images) {
      if (image.status != ImageStatus::kCaptured || image.capture.value("group", 0) != g) continue;
      const auto t = image.capture["trigger_unix_ns"].get<std::int64_t>();
      lo = std::min(lo, t);
      hi = std::max(hi, t);
      ++report.fired;
    }
    if (lo <= hi) report.skew_ms = std::max(report.skew_ms.value_or(0.0), double(hi - lo) / 1e6);
  }

  Shot shot{options.kind, shot_name, {}, std::move(images)};
  manifest.shots.push_back(std::move(shot));
  {
    ManifestKeeper keeper(session, manifest);
    keeper.Update([](CaptureManifest&) {});
    keeper.Flush();
  }
  CollectProblems(manifest, report);
  if (!options.fetch) return report;

  const SessionReport fetched = FetchSession(array, key, session, options.fetch_options);
  report.fetch_s = fetched.fetch_s;
  report.bytes = fetched.bytes;
  report.images_ok = fetched.images_ok;
  report.problems = fetched.problems;
  return report;
}

nlohmann::json SessionReportToJson(const SessionReport& r) {
  nlohmann::json problems = nlohmann::json::array();
  for (const CameraProblem& p : r.problems)
    problems.push_back({{"row", p.row},
                        {"col", p.col},
                        {"shot", p.shot},
                        {"status", p.status},
                        {"reason", p.reason}});
  return {{"shot", r.shot},
          {"cameras", r.cameras},
          {"fired", r.fired},
          {"skew_ms", r.skew_ms ? nlohmann::json(*r.skew_ms) : nlohmann::json()},
          {"trigger_margin_s", r.trigger_wait_s},
          {"capture_s", r.capture_s},
          {"fetch_s", r.fetch_s},
          {"bytes", r.bytes},
          {"images_ok", r.images_ok},
          {"problems", problems}};
}

}  // namespace lfcam
