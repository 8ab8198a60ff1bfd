#pragma once
// What a node reports of its machine: CPU temperature and throttling (a Raspberry Pi that runs
// hot slows down), free disk and memory, and how far its clock is from the array's time source
// as chrony sees it. Each is empty where the machine does not say.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace lfcam {

struct ClockOffset {
  double offset_ms = 0;  // this clock minus the reference, milliseconds
  std::string source;    // "chrony (server 10.0.0.1)", "simulated"
};

struct SystemStatus {
  std::string machine;  // the instruction set it runs (uname -m): "aarch64"
  std::optional<double> cpu_temperature_c;
  std::optional<std::string> throttled;  // vcgencmd get_throttled, e.g. "0x0"
  std::uint64_t disk_free_bytes = 0;
  std::optional<std::uint64_t> memory_available_bytes;
  std::optional<ClockOffset> clock;
};

// `folder`: the capture folder, whose file system's free space counts.
SystemStatus ReadSystemStatus(const std::filesystem::path& folder);

// chrony's view of this clock (`chronyc -c tracking`, a process of its own, started without a
// shell), read again when the last reading is older than `max_age`; nullopt when chrony is not
// running or not synchronised, and at once, starting nothing, when the agent found no chronyc on
// its PATH as it started (install chrony, then restart the agent).
std::optional<ClockOffset> ChronyClockOffset(std::chrono::steady_clock::duration max_age);
// A status request reads the clock afresh (ReadSystemStatus). A capture request, between its
// arrival and its trigger time, takes the reading the host's status request just before it made
// (`lfcam capture shoot` asks every node's status first), so that no process starts in that
// window: a hundred nodes on one machine each starting one made triggers late (docs/robustness.md).
inline constexpr std::chrono::seconds kStatusClockMaxAge{1};
inline constexpr std::chrono::seconds kCaptureClockMaxAge{60};

// Parses one line of `chronyc -c tracking` (CSV); nullopt when it is not one.
std::optional<ClockOffset> ParseChronyTracking(const std::string& line);

nlohmann::json SystemStatusToJson(const SystemStatus& status);

}  // namespace lfcam
