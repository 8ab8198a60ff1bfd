// `lfcam capture`: the host controller of a camera array of lfcam-node agents (docs/hardware.md).
#include <fcntl.h>
#include <fmt/core.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include "lfcam/capture/ansible_inventory.h"
#include "lfcam/capture/array_file.h"
#include "lfcam/capture/array_status.h"
#include "lfcam/capture/capture_session.h"
#include "lfcam/capture/node_client.h"
#include "lfcam/capture/recording_report.h"
#include "lfcam/capture/recording_session.h"
#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"

namespace lfcam::cli {
namespace {

namespace fs = std::filesystem;

// What every subcommand that talks to the nodes takes: the array file and the key.
struct ArrayFlags {
  std::string array, key_file;
  bool json = false;

  void Add(CLI::App* command) {
    command->add_option("array", array, "The array file (lfcam capture init writes one)")
        ->required();
    command->add_option("--key-file", key_file, "The array's key (default: the array file's)");
    command->add_flag("--json", json, "Print the result as JSON");
  }
  std::pair<ArrayConfig, SharedKey> Load() const {
    ArrayConfig config = ReadArrayFile(array);
    const fs::path key_path = key_file.empty() ? KeyFilePath(config, array) : fs::path(key_file);
    SharedKey key = ReadKeyFile(key_path);
    return {std::move(config), std::move(key)};
  }
};

void PrintReports(const std::vector<NodeReport>& reports, bool json) {
  if (json)
    fmt::print("{}\n", JsonToText(ReportsToJson(reports), 2));
  else
    fmt::print("{}", ReportsTable(reports, ::isatty(STDOUT_FILENO) == 1));
}

// A session that is not complete exits with status 1, after the report (JSON or text).
// `fetched`: false for --no-fetch, where images the nodes took and hold are what was asked for,
// not problems: they are counted and the command says how to bring them home.
void FinishSession(SessionReport report, const fs::path& session, bool json, bool fetched = true) {
  int left_on_nodes = 0;
  if (!fetched) {
    const auto held = [](const CameraProblem& p) { return p.status == "captured"; };
    left_on_nodes = int(std::count_if(report.problems.begin(), report.problems.end(), held));
    std::erase_if(report.problems, held);
  }
  if (json) {
    nlohmann::json j = SessionReportToJson(report);
    j["session"] = session.string();
    j["complete"] = report.problems.empty();
    j["left_on_nodes"] = left_on_nodes;
    fmt::print("{}\n", JsonToText(j, 2));
    std::fflush(stdout);
    if (!report.problems.empty()) std::exit(1);
    return;
  }
  if (!report.shot.empty()) {
    fmt::print("{} '{}': {} of {} cameras {}", report.video ? "recording" : "shot", report.shot,
               report.fired, report.cameras, report.video ? "recorded" : "fired");
    if (report.skew_ms) fmt::print(", trigger skew {:.3f} ms", *report.skew_ms);
    fmt::print(" ({:.2f} s from request to last {} taken, margin {:.2f} s)\n", report.capture_s,
               report.video ? "frame" : "image", report.trigger_wait_s);
  }
  if (fetched)
    fmt::print("fetched {:.1f} MB in {:.2f} s; {} images in {}\n", double(report.bytes) / 1e6,
               report.fetch_s, report.images_ok, session.string());
  else
    fmt::print(
        "{} {} left on the nodes (--no-fetch): `lfcam capture fetch ARRAY --session {}` "
        "brings them home\n",
        left_on_nodes, report.video ? "recordings" : "images", session.string());
  if (report.problems.empty()) return;
  for (const CameraProblem& p : report.problems)
    fmt::print(stderr, "  {} {} in shot '{}': {}\n", CameraLabel(p.row, p.col), p.status, p.shot,
               p.reason);
  int captured = 0;
  for (const CameraProblem& p : report.problems) captured += p.status == "captured";
  throw Error(fmt::format(
      "{} images are not in the session ({} still on their nodes{}); the manifest says why",
      report.problems.size(), captured,
      captured > 0 ? ": `lfcam capture fetch` gets them when the nodes are back" : ""));
}

void AddKeygen(CLI::App& capture) {
  auto* command = capture.add_subcommand("keygen", "Write a new key for an array (mode 600)");
  auto out = std::make_shared<std::string>();
  command->add_option("--out", *out, "The key file to write (must not exist)")->required();
  command->callback([out] {
    const int fd = ::open(out->c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
    if (fd < 0)
      throw UsageError(
          fmt::format("--out {}: cannot create ({}); an existing key is never "
                      "overwritten",
                      *out, std::strerror(errno)));
    const std::string text = NewKeyHex() + "\n";
    const bool ok = ::write(fd, text.data(), text.size()) == ssize_t(text.size());
    ::close(fd);
    if (!ok) {
      ::unlink(out->c_str());
      throw Error(fmt::format("{}: write failed", *out));
    }
    fmt::print("wrote {}: copy it to every node (mode 600) and keep it off the network\n", *out);
  });
}

void AddInit(CLI::App& capture) {
  auto* command = capture.add_subcommand("init", "Write an array file: grid, node addresses, key");
  struct Flags {
    std::string out, grid = "10x10", addresses, key_file = "array.key", sensor = "2592x1944",
                     intrinsics_board, world_board;
    double pitch = 28.0;
  };
  auto f = std::make_shared<Flags>();
  command->add_option("--out", f->out, "The array file to write")->required();
  command->add_option("--grid", f->grid, "ROWSxCOLS")->capture_default_str();
  command
      ->add_option("--addresses", f->addresses,
                   "Node address pattern with {row} {col} {row02} {col02} {index} {index1}, e.g. "
                   "10.0.0.{index1}:8470")
      ->required();
  command->add_option("--key-file", f->key_file, "The key, relative to the array file")
      ->capture_default_str();
  command->add_option("--pitch", f->pitch, "Camera spacing, mm")->capture_default_str();
  command->add_option("--sensor", f->sensor, "Image size WxH")->capture_default_str();
  command->add_option("--intrinsics-board", f->intrinsics_board, "The intrinsics board's SPEC");
  command->add_option("--world-board", f->world_board, "The world board's SPEC");
  command->callback([f] {
    ArrayConfig a;
    std::tie(a.rows, a.cols) = ParseSize("--grid", f->grid, kMaxViewsPerSide);
    std::tie(a.settings.width, a.settings.height) = ParseSize("--sensor", f->sensor, 16384);
    if (!(f->pitch > 0)) throw UsageError("--pitch must be positive");
    a.pitch_mm = f->pitch;
    a.key_file = f->key_file;
    a.nodes = NodesFromPattern(a.rows, a.cols, f->addresses);
    if (!f->intrinsics_board.empty())
      a.intrinsics_board =
          FlagValue("--intrinsics-board", [&] { return ParseBoardSpec(f->intrinsics_board); });
    if (!f->world_board.empty())
      a.world_board = FlagValue("--world-board", [&] { return ParseBoardSpec(f->world_board); });
    WriteArrayFile(f->out, a);
    fmt::print("wrote {}: {}x{} nodes, {} to {}\n", f->out, a.rows, a.cols, a.nodes.front().address,
               a.nodes.back().address);
  });
}

void AddStatus(CLI::App& capture) {
  auto* command = capture.add_subcommand("status", "Every node's health, in one table");
  struct Flags : ArrayFlags {
    std::string session;
  };
  auto flags = std::make_shared<Flags>();
  flags->Add(command);
  command->add_option("--session", flags->session,
                      "Also say how well the array kept in step in each of its recordings");
  command->callback([flags] {
    const auto [array, key] = flags->Load();
    const std::vector<NodeReport> reports = ArrayStatus(array, key);
    if (flags->session.empty()) return PrintReports(reports, flags->json);
    const CaptureManifest manifest = ReadManifest(flags->session);
    std::vector<RecordingReport> recordings;
    for (const Shot& s : manifest.shots)
      if (s.kind == ShotKind::kVideo) recordings.push_back(MakeRecordingReport(manifest, s.name));
    if (flags->json) {
      nlohmann::json j = ReportsToJson(reports);
      j["recordings"] = nlohmann::json::array();
      for (const RecordingReport& r : recordings) {
        nlohmann::json one = RecordingReportToJson(r);
        one.erase("per_frame");
        one.erase("per_camera");
        j["recordings"].push_back(std::move(one));
      }
      fmt::print("{}\n", JsonToText(j, 2));
      return;
    }
    PrintReports(reports, false);
    for (const RecordingReport& r : recordings) fmt::print("\n{}", RecordingReportText(r));
  });
}

void AddReport(CLI::App& capture) {
  auto* command = capture.add_subcommand(
      "report", "How well the array kept in step over a recording: spread, missing frames");
  struct Flags {
    std::string session, shot, out;
    bool json = false;
  };
  auto f = std::make_shared<Flags>();
  command->add_option("--session", f->session, "The session folder")->required();
  command->add_option("--shot", f->shot, "The recording (default: the session's last)");
  command->add_option("--out", f->out,
                      "Also draw the spread over time and each camera's offsets into this PNG");
  command->add_flag("--json", f->json, "Print the report as JSON (every frame and camera)");
  command->callback([f] {
    if (!f->out.empty()) RequireImageOutput(f->out, "--out");
    const RecordingReport report = MakeRecordingReport(ReadManifest(f->session), f->shot);
    if (!f->out.empty()) WriteImage(f->out, RecordingReportPicture(report));
    if (f->json)
      fmt::print("{}\n", JsonToText(RecordingReportToJson(report), 2));
    else
      fmt::print("{}", RecordingReportText(report));
  });
}

void AddConfigure(CLI::App& capture) {
  auto* command = capture.add_subcommand(
      "configure", "Lock the same camera settings on every node (flags update the array file)");
  struct Flags : ArrayFlags {
    std::string size, awb, denoise;
    int exposure_us = 0, quality = 0;
    double gain = 0;
  };
  auto f = std::make_shared<Flags>();
  f->Add(command);
  command->add_option("--size", f->size, "Image size WxH");
  command->add_option("--exposure-us", f->exposure_us, "Shutter time, microseconds");
  command->add_option("--gain", f->gain, "Analogue gain, 1..16");
  command->add_option("--awb", f->awb, "White-balance gains RED,BLUE");
  command->add_option("--denoise", f->denoise, "off, cdn_off, cdn_fast or cdn_hq");
  command->add_option("--quality", f->quality, "JPEG quality, 1..100");
  command->callback([f] {
    // Named, not a structured binding: the lambda below captures the array (clang 14 cannot
    // capture a structured binding).
    auto loaded = f->Load();
    ArrayConfig& array = loaded.first;
    const SharedKey& key = loaded.second;
    nlohmann::json changes = nlohmann::json::object();
    if (!f->size.empty()) {
      const auto [w, h] = ParseSize("--size", f->size, 16384);
      changes["width"] = w;
      changes["height"] = h;
    }
    if (f->exposure_us != 0) changes["exposure_us"] = f->exposure_us;
    if (f->gain != 0) changes["analogue_gain"] = f->gain;
    if (!f->awb.empty()) {
      const auto gains = ParseNumbers("--awb", f->awb, 2);
      changes["awb_gains"] = {gains[0], gains[1]};
    }
    if (!f->denoise.empty()) changes["denoise"] = f->denoise;
    if (f->quality != 0) changes["jpeg_quality"] = f->quality;
    if (!changes.empty()) {
      array.settings = FlagValue("settings", [&] {
        return SettingsFromJson(changes, "the settings flags", array.settings);
      });
      ArrayConfig on_disk = ReadArrayFile(f->array);
      on_disk.settings = array.settings;
      WriteArrayFile(f->array, on_disk);
      if (!f->json) fmt::print("updated the settings in {}\n", f->array);
    }
    PrintReports(ConfigureArray(array, key), f->json);
  });
}

void AddIdentify(CLI::App& capture) {
  auto* command =
      capture.add_subcommand("identify", "Make one node blink its activity LED and log loudly");
  struct Flags : ArrayFlags {
    std::string camera;
    int seconds = 10;
  };
  auto f = std::make_shared<Flags>();
  f->Add(command);
  command->add_option("--camera", f->camera, "ROW,COL")->required();
  command->add_option("--seconds", f->seconds, "How long")
      ->capture_default_str()
      ->check(CLI::Range(1, 600));
  command->callback([f] {
    const auto [array, key] = f->Load();
    const auto rc = ParseNumbers("--camera", f->camera, 2);
    const ArrayNode* node = array.node_at(int(rc[0]), int(rc[1]));
    if (!node)
      throw UsageError(fmt::format("--camera {}: no such node in {}", f->camera, f->array));
    NodeClient client(node->address, key);
    const auto reply = client.Post("/v1/identify", {{"seconds", f->seconds}});
    if (f->json)
      fmt::print("{}\n", JsonToText(reply.body, 2));
    else
      fmt::print("{} ({}): {}\n", CameraLabel(node->row, node->col), node->address,
                 reply.body.value("led", false) ? "blinking its activity LED"
                                                : "no LED access; it is logging loudly");
  });
}

void AddPreview(CLI::App& capture) {
  auto* command = capture.add_subcommand(
      "preview", "A contact sheet of every node's preview, laid out as the array");
  struct Flags : ArrayFlags {
    std::string out;
    int tile_width = 256;
  };
  auto f = std::make_shared<Flags>();
  f->Add(command);
  command->add_option("--out", f->out, "The contact sheet (.png or .jpg)")->required();
  command->add_option("--tile-width", f->tile_width, "Pixels per node")
      ->capture_default_str()
      ->check(CLI::Range(32, 1024));
  command->callback([f] {
    RequireImageOutput(f->out, "--out");
    const auto [array, key] = f->Load();
    WriteImage(f->out, PreviewSheet(array, key, f->tile_width));
    if (!f->json) fmt::print("wrote {}\n", f->out);
  });
}

void AddFetchFlags(CLI::App* command, FetchOptions& o) {
  command->add_option("--concurrency", o.concurrency, "Downloads at once")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  command->add_option("--retries", o.retries, "Tries per image after the first (with backoff)")
      ->capture_default_str()
      ->check(CLI::Range(0, 20));
}

void AddShoot(CLI::App& capture) {
  auto* command = capture.add_subcommand(
      "shoot", "Fire every node at one scheduled time, then fetch the images into a session");
  struct Flags : ArrayFlags {
    std::string session, kind = "scene";
    ShootOptions o;
    bool no_fetch = false, quiet = false;
  };
  auto f = std::make_shared<Flags>();
  f->Add(command);
  command->add_option("--session", f->session, "The session folder (created or extended)")
      ->required();
  command->add_option("--kind", f->kind, "scene, world or intrinsics (one board pose)")
      ->capture_default_str();
  command->add_option("--groups", f->o.groups, "Fire in this many groups (the paper: 2)")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  command->add_option("--group-delay", f->o.group_delay_s, "Seconds between groups")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  command->add_option("--margin", f->o.margin_s, "Seconds from now to the trigger time")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 60.0));
  command
      ->add_option("--capture-timeout", f->o.capture_timeout_s,
                   "Seconds a node has to store its image after the trigger")
      ->capture_default_str();
  AddFetchFlags(command, f->o.fetch_options);
  command->add_flag("--no-fetch", f->no_fetch, "Leave the images on the nodes (fetch later)");
  command->add_flag("--quiet", f->quiet, "No progress bar");
  command->callback([f] {
    if (f->kind == "scene")
      f->o.kind = ShotKind::kScene;
    else if (f->kind == "world")
      f->o.kind = ShotKind::kWorld;
    else if (f->kind == "intrinsics")
      f->o.kind = ShotKind::kIntrinsics;
    else
      throw UsageError(fmt::format("--kind '{}' is not scene, world or intrinsics", f->kind));
    f->o.fetch = !f->no_fetch;
    const auto [array, key] = f->Load();
    ProgressBar progress("fetching", std::int64_t(array.nodes.size()),
                         ProgressWanted(f->quiet || f->json));
    if (auto advance = progress.callback())
      f->o.fetch_options.progress = [advance](std::int64_t) { advance(1); };
    const SessionReport report = ShootSession(array, key, f->session, f->o);
    progress.finish();
    FinishSession(report, f->session, f->json, f->o.fetch);
  });
}

void AddRecord(CLI::App& capture) {
  auto* command = capture.add_subcommand(
      "record", "Record video on every node from one start time, then fetch the recordings");
  struct Flags : ArrayFlags {
    std::string session, size = "648x486";
    RecordOptions o;
    bool no_sync = false, no_fetch = false, quiet = false;
  };
  auto f = std::make_shared<Flags>();
  f->Add(command);
  command->add_option("--session", f->session, "The session folder (created or extended)")
      ->required();
  command->add_option("--seconds", f->o.seconds, "How long to record")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 3600.0));
  command->add_option("--fps", f->o.fps, "Frames a second")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1000.0));
  command
      ->add_option("--size", f->size,
                   "The video's sensor mode, WIDTHxHEIGHT (the Pi v1.3's: 648x486, 1296x972)")
      ->capture_default_str();
  command->add_flag("--no-sync", f->no_sync,
                    "Free-running cameras (a shared start time only; no libcamera sync)");
  command
      ->add_option("--stagger", f->o.stagger,
                   "High-speed mode: N groups of cameras whose frames start 1/(N fps) apart, "
                   "together sampling time N times as often (the array file's groups, else "
                   "interleaved)")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  command->add_option("--margin", f->o.margin_s, "Seconds from now to the start")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 60.0));
  command
      ->add_option("--finish-timeout", f->o.finish_timeout_s,
                   "After the end, seconds without a new frame from any node before the host "
                   "stops waiting for those still recording")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 86400.0));
  AddFetchFlags(command, f->o.fetch_options);
  command->add_flag("--no-fetch", f->no_fetch, "Leave the recordings on the nodes (fetch later)");
  command->add_flag("--quiet", f->quiet, "No progress bar");
  command->callback([f] {
    char x = 0;
    if (std::sscanf(f->size.c_str(), "%dx%d%c", &f->o.width, &f->o.height, &x) != 2)
      throw UsageError(fmt::format("--size '{}': expected WIDTHxHEIGHT", f->size));
    f->o.sync = !f->no_sync;
    f->o.fetch = !f->no_fetch;
    const auto [array, key] = f->Load();
    const auto frames = std::int64_t(double(array.nodes.size()) * f->o.fps * f->o.seconds + 0.5);
    ProgressBar recording("recording", frames, ProgressWanted(f->quiet || f->json));
    if (auto advance = recording.callback()) f->o.progress = advance;
    f->o.fetch_options.progress = [&recording](std::int64_t) { recording.finish(); };
    SessionReport report = RecordSession(array, key, f->session, f->o);
    recording.finish();
    report.video = true;
    if (!f->json)
      fmt::print("{}",
                 RecordingReportText(MakeRecordingReport(ReadManifest(f->session), report.shot)));
    FinishSession(report, f->session, f->json, f->o.fetch);
  });
}

void AddFetch(CLI::App& capture) {
  auto* command = capture.add_subcommand(
      "fetch", "Download whatever a session's nodes hold and the session does not yet");
  struct Flags : ArrayFlags {
    std::string session;
    FetchOptions o;
    bool quiet = false;
  };
  auto f = std::make_shared<Flags>();
  f->Add(command);
  command->add_option("--session", f->session, "The session folder")->required();
  AddFetchFlags(command, f->o);
  command->add_flag("--quiet", f->quiet, "No progress bar");
  command->callback([f] {
    const auto [array, key] = f->Load();
    std::error_code ec;
    const CaptureManifest manifest = fs::is_regular_file(fs::path(f->session) / kManifestName, ec)
                                         ? ReadManifest(f->session)
                                         : CaptureManifest{};
    std::int64_t waiting = 0;
    for (const Shot& s : manifest.shots)
      for (const ShotImage& i : s.pending) waiting += i.status == ImageStatus::kCaptured;
    ProgressBar progress("fetching", waiting, ProgressWanted(f->quiet || f->json));
    if (auto advance = progress.callback()) f->o.progress = [advance](std::int64_t) { advance(1); };
    const SessionReport report = FetchSession(array, key, f->session, f->o);
    progress.finish();
    FinishSession(report, f->session, f->json);
  });
}

void AddInventory(CLI::App& capture) {
  auto* command = capture.add_subcommand(
      "inventory",
      "Write the array as an Ansible inventory, for the playbook that installs every node "
      "(deploy/ansible/lfcam-node.yml)");
  struct Flags {
    std::string array, out, ssh_user, chrony_server, package;
  };
  auto f = std::make_shared<Flags>();
  command->add_option("array", f->array, "The array file")->required();
  command->add_option("--out", f->out, "The inventory to write (YAML; default: standard output)");
  command->add_option("--ssh-user", f->ssh_user, "The user Ansible logs in to the nodes as");
  command->add_option("--chrony-server", f->chrony_server,
                      "The time server the nodes follow (the host's address on the array's LAN)");
  command->add_option("--package", f->package,
                      "The lfcam-node .deb the playbook installs (scripts/package.sh)");
  command->callback([f] {
    if (!f->out.empty()) RequireWritableOutput(f->out, "--out");
    if (!f->package.empty() && !fs::is_regular_file(f->package))
      throw UsageError(fmt::format("--package {}: no such file", f->package));
    const ArrayConfig array = ReadArrayFile(f->array);
    InventoryOptions options;
    options.ssh_user = f->ssh_user;
    options.chrony_server = f->chrony_server;
    options.node_package = f->package;
    const std::string text = AnsibleInventory(array, f->array, options);
    if (f->out.empty()) {
      fmt::print("{}", text);
      return;
    }
    WriteFileAtomically(f->out, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
    fmt::print(stderr,
               "wrote {}: {} nodes; then: ansible-playbook -i {} deploy/ansible/lfcam-node.yml\n",
               f->out, array.nodes.size(), f->out);
  });
}

}  // namespace

void AddCaptureCommand(CLI::App& app) {
  auto* capture = app.add_subcommand(
      "capture",
      "Drive a camera array of lfcam-node agents: status, configure, shoot, record, fetch");
  capture->require_subcommand(1);
  AddKeygen(*capture);
  AddInit(*capture);
  AddStatus(*capture);
  AddConfigure(*capture);
  AddIdentify(*capture);
  AddPreview(*capture);
  AddShoot(*capture);
  AddRecord(*capture);
  AddFetch(*capture);
  AddReport(*capture);
  AddInventory(*capture);
}

}  // namespace lfcam::cli
