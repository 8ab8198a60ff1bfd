#pragma once
// lfcam-node, the agent on every Raspberry Pi of the array: an HTTP/1.1 API on the LAN
// (cpp-httplib) through which the host reads the node's health, locks its camera settings,
// schedules a capture at a wall-clock time, and downloads what it took. Every request is signed
// with the array's key (request_signature.h). docs/hardware.md describes the API.
//
//   GET    /v1/status              agent, camera, settings, machine, clock, captures held
//   POST   /v1/configure           {settings}: lock the camera's settings
//   POST   /v1/capture             {id, kind, shot, at_unix_ns, settings}: fire at T
//   GET    /v1/captures            the captures held (records)
//   GET    /v1/captures/ID         the image or recorded stream (Range supported; X-Lfcam-Sha256)
//   DELETE /v1/captures/ID
//   POST   /v1/record              {id, shot, at_unix_ns, video, settings}: record from T (202)
//   GET    /v1/recordings/ID       a recording's record and frame index (while it records too)
//   POST   /v1/identify            {seconds}: blink the activity LED, log loudly
//   GET    /v1/preview?width=W     a small JPEG for aiming
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "lfcam/node/camera_backend.h"
#include "lfcam/node/request_signature.h"

namespace lfcam {

inline constexpr const char* kNodeAgentVersion = "1";
inline constexpr std::size_t kMaxRequestBodyBytes = 64 * 1024;

// Faults a test can make a node show (never on a real node): slow, corrupting downloads.
struct NodeFaults {
  double download_bytes_per_s = 0;  // 0: as fast as it goes
  bool corrupt_downloads = false;   // flip one byte in the middle of every image sent
};

struct NodeOptions {
  std::string name;                // shown in status and logs, e.g. "cam_03_07"
  std::filesystem::path captures;  // where captures are kept
  SharedKey key;
  std::chrono::milliseconds signature_window{30'000};
  double max_clock_offset_ms = 10.0;  // refuse to capture beyond this (chrony's offset)
  std::uint64_t min_free_bytes = std::uint64_t(256) << 20;  // refuse to capture below this
  std::int64_t simulated_clock_offset_ns = 0;  // tests: this node's clock is wrong by this much
  NodeFaults faults;
  int threads = 4;
  bool quiet = false;  // no log line per request
};

class NodeAgent {
 public:
  NodeAgent(NodeOptions options, std::unique_ptr<CameraBackend> camera);
  ~NodeAgent();
  NodeAgent(const NodeAgent&) = delete;
  NodeAgent& operator=(const NodeAgent&) = delete;

  // Binds to host:port (port 0: any free port) and returns the port. Throws lfcam::Error.
  int Bind(const std::string& host, int port);
  // Serves until Stop (from another thread or a signal handler's thread).
  void Serve();
  void Stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The node's wall clock: the system's, plus the simulated offset (tests).
std::int64_t NodeClockUnixNs(std::int64_t simulated_offset_ns);

}  // namespace lfcam
