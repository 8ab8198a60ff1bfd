// lfcam-node: the agent on each Raspberry Pi of the array (docs/hardware.md). It serves the
// node's camera on the LAN to the host's `lfcam capture`, every request signed with the array's
// key. This file only parses flags and starts the agent (node_agent.h).
#include <fmt/core.h>
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <thread>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/node/node_agent.h"
#include "lfcam/node/replay_camera.h"
#include "lfcam/node/rpicam_camera.h"
#ifdef LFCAM_NODE_WITH_SIMULATOR
#include "lfcam/node/simulated_camera.h"
#endif

namespace {

std::pair<std::string, int> ParseListen(const std::string& text) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw lfcam::UsageError(fmt::format("--listen '{}': expected HOST:PORT", text));
  try {
    std::size_t used = 0;
    const int port = std::stoi(text.substr(colon + 1), &used);
    if (used != text.size() - colon - 1 || port < 0 || port > 65535) throw std::out_of_range("");
    return {text.substr(0, colon), port};
  } catch (const std::exception&) {
    throw lfcam::UsageError(fmt::format("--listen '{}': the port must be 0..65535", text));
  }
}

std::string HostName() {
  char name[256] = {};
  ::gethostname(name, sizeof name - 1);
  return name[0] ? name : "node";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lfcam-node: the capture agent on each Raspberry Pi of an lfcam array"};
  app.set_version_flag("--version", std::string("lfcam-node " LFCAM_VERSION " (API v") +
                                        lfcam::kNodeAgentVersion + ")");
  std::string listen = "0.0.0.0:8470", key_file, backend = "rpicam", port_file;
  std::string captures = "/var/lib/lfcam-node/captures", name;
  lfcam::RpicamOptions rpicam;
  std::string replay;
  double min_free_mb = 256, window_s = 30, simulated_offset_ms = 0, download_rate = 0;
  lfcam::NodeOptions options;
  app.add_option("--listen", listen, "HOST:PORT to serve on (port 0: any free port)")
      ->capture_default_str();
  app.add_option("--key-file", key_file, "The array's key (64 hex digits, mode 600)")->required();
  app.add_option("--captures", captures, "Folder for the captures this node holds")
      ->capture_default_str();
  app.add_option("--name", name, "This node's name in status and logs (default: host name)");
  app.add_option("--backend", backend,
                 "Camera: rpicam (a Raspberry Pi camera), replay"
#ifdef LFCAM_NODE_WITH_SIMULATOR
                 ", sim (the simulated module)"
#endif
                 )
      ->capture_default_str();
  app.add_option("--rpicam-command", rpicam.command,
                 "rpicam: the camera command template (docs/hardware.md)")
      ->capture_default_str();
  app.add_option("--rpicam-program", rpicam.program,
                 "rpicam: the program for {program} (default: rpicam-still, else libcamera-still)");
  app.add_option("--rpicam-video-command", rpicam.video_command,
                 "rpicam: the video command template (docs/hardware.md)")
      ->capture_default_str();
  app.add_option("--rpicam-video-program", rpicam.video_program,
                 "rpicam: the program for a video's {program} (default: rpicam-vid, else "
                 "libcamera-vid)");
  app.add_option("--rpicam-sync-frames", rpicam.sync_warmup_frames,
                 "rpicam: frames the sync server counts before the clients follow (rpicam-apps' "
                 "--sync-frames)")
      ->capture_default_str()
      ->check(CLI::Range(0, 10000));
  app.add_option("--rpicam-warmup-ms", rpicam.warmup_ms,
                 "rpicam: wait after starting the camera before the first trigger")
      ->capture_default_str();
  app.add_option("--replay", replay, "replay: the folder of images (SHOT.jpg or KIND.jpg)");
#ifdef LFCAM_NODE_WITH_SIMULATOR
  lfcam::SimulatedCameraOptions sim;
  std::string sim_position, sim_grid = "10x10";
  app.add_option("--sim-position", sim_position, "sim: this node's ROW,COL in the array");
  app.add_option("--sim-grid", sim_grid, "sim: the array's ROWSxCOLS")->capture_default_str();
  app.add_option("--sim-seed", sim.seed, "sim: the array's seed (as simulate capture --seed)")
      ->capture_default_str();
  app.add_option("--sim-defects", sim.defects, "sim: realistic or none")->capture_default_str();
  app.add_option("--sim-board", sim.board, "sim: the intrinsics board, chessboard or charuco")
      ->capture_default_str();
  app.add_option("--sim-clock-offset-us", sim.clock_offset_us,
                 "sim video: how far this node's wall clock may be off true time (+-)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e7));
  app.add_option("--sim-drop-rate", sim.drop_rate, "sim video: a frame's chance of being dropped")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
#endif
  app.add_option("--max-clock-offset-ms", options.max_clock_offset_ms,
                 "Refuse to capture when chrony's offset exceeds this")
      ->capture_default_str();
  app.add_option("--min-free-mb", min_free_mb, "Refuse to capture with less disk free")
      ->capture_default_str();
  app.add_option("--signature-window-s", window_s,
                 "Refuse requests signed further than this from the node's clock")
      ->capture_default_str();
  app.add_option("--threads", options.threads, "HTTP worker threads")->capture_default_str();
  app.add_option("--port-file", port_file, "Write the port served on to this file");
  app.add_flag("--quiet", options.quiet, "No log line per request");
  auto* testing = app.add_option_group("Testing", "Faults for the capture system's tests");
  testing->add_option("--simulate-clock-offset-ms", simulated_offset_ms,
                      "This node's clock reads this far off");
  testing->add_option("--fault-download-rate", download_rate,
                      "Send downloads at most this fast (bytes/s)");
  testing->add_flag("--fault-corrupt-downloads", options.faults.corrupt_downloads,
                    "Flip a byte in every image sent");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  // Signals are taken by a thread of their own, so that every other thread runs unbothered.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  ::signal(SIGPIPE, SIG_IGN);

  try {
    const auto [host, port] = ParseListen(listen);
    options.name = name.empty() ? HostName() : name;
    options.captures = captures;
    options.key = lfcam::ReadKeyFile(key_file);
    options.signature_window = std::chrono::milliseconds(std::int64_t(window_s * 1000));
    options.min_free_bytes = std::uint64_t(min_free_mb * 1e6);
    options.simulated_clock_offset_ns = std::int64_t(simulated_offset_ms * 1e6);
    options.faults.download_bytes_per_s = download_rate;

    std::unique_ptr<lfcam::CameraBackend> camera;
    if (backend == "rpicam") {
      rpicam.work_folder = std::filesystem::path(captures) / ".camera";
      camera = lfcam::MakeRpicamCamera(rpicam);
    } else if (backend == "replay") {
      if (replay.empty()) throw lfcam::UsageError("--backend replay needs --replay FOLDER");
      camera = lfcam::MakeReplayCamera(replay);
#ifdef LFCAM_NODE_WITH_SIMULATOR
    } else if (backend == "sim") {
      if (std::sscanf(sim_position.c_str(), "%d,%d", &sim.row, &sim.col) != 2)
        throw lfcam::UsageError("--backend sim needs --sim-position ROW,COL");
      if (std::sscanf(sim_grid.c_str(), "%dx%d", &sim.rows, &sim.cols) != 2)
        throw lfcam::UsageError(fmt::format("--sim-grid '{}': expected ROWSxCOLS", sim_grid));
      camera = lfcam::MakeSimulatedCamera(sim);
#endif
    } else {
      throw lfcam::UsageError(fmt::format("--backend '{}' is not a camera backend here", backend));
    }

    lfcam::NodeAgent agent(options, std::move(camera));
    const int bound = agent.Bind(host, port);
    if (!port_file.empty()) {
      const std::string text = std::to_string(bound) + "\n";
      lfcam::WriteFileAtomically(port_file,
                                 {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
    }
    fmt::print(stderr, "lfcam-node {}: serving {} on {}:{}\n", options.name, backend, host, bound);
    std::thread waiter([&agent, signals] {
      int sig = 0;
      sigwait(&signals, &sig);
      agent.Stop();
    });
    waiter.detach();
    agent.Serve();
    return 0;
  } catch (const lfcam::UsageError& e) {
    fmt::print(stderr, "lfcam-node: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "lfcam-node: error: {}\n", e.what());
    return 1;
  }
}
