#include "lfcam/node/system_status.h"

#include <fmt/format.h>
#include <sys/statvfs.h>
#include <sys/utsname.h>

#include <chrono>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

#include "lfcam/node/program_output.h"

namespace lfcam {

std::optional<ClockOffset> ParseChronyTracking(const std::string& line) {
  // Reference ID, name, stratum, reference time, system time offset (s), last offset (s), ...
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  if (fields.size() < 6) return std::nullopt;
  try {
    std::size_t used = 0;
    const double system_offset_s = std::stod(fields[4], &used);
    if (used != fields[4].size()) return std::nullopt;
    const int stratum = std::stoi(fields[2]);
    if (stratum <= 0 || stratum >= 16) return std::nullopt;  // not synchronised
    return ClockOffset{system_offset_s * 1000.0, fmt::format("chrony (server {})", fields[1])};
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<ClockOffset> ChronyClockOffset(std::chrono::steady_clock::duration max_age) {
  static std::mutex mutex;
  static std::chrono::steady_clock::time_point read_at;
  static std::optional<ClockOffset> cached;
  static bool ever = false;
  std::lock_guard lock(mutex);
  const auto now = std::chrono::steady_clock::now();
  if (!ever || now - read_at > max_age) {
    // Looked for once: where chrony is not installed no process starts (a status request on a
    // machine of a hundred agents started a hundred shells that each found nothing).
    static const bool has_chronyc = !FindOnPath({"chronyc"}).empty();
    const auto line =
        has_chronyc ? FirstLineOfProgram({"chronyc", "-c", "tracking"}) : std::nullopt;
    cached = line ? ParseChronyTracking(*line) : std::nullopt;
    read_at = now;
    ever = true;
  }
  return cached;
}

SystemStatus ReadSystemStatus(const std::filesystem::path& folder) {
  SystemStatus s;
  if (utsname u{}; ::uname(&u) == 0) s.machine = u.machine;
  if (std::ifstream t("/sys/class/thermal/thermal_zone0/temp"); t) {
    double milli = 0;
    if (t >> milli) s.cpu_temperature_c = milli / 1000.0;
  }
  static const bool has_vcgencmd = !FindOnPath({"vcgencmd"}).empty();
  if (has_vcgencmd)
    if (auto line = FirstLineOfProgram({"vcgencmd", "get_throttled"})) {
      const auto eq = line->find('=');
      s.throttled = eq == std::string::npos ? *line : line->substr(eq + 1);
    }
  struct statvfs st {};
  if (::statvfs(folder.c_str(), &st) == 0)
    s.disk_free_bytes = std::uint64_t(st.f_bavail) * st.f_frsize;
  if (std::ifstream m("/proc/meminfo"); m) {
    std::string key;
    std::uint64_t kib = 0;
    std::string unit;
    while (m >> key >> kib >> unit)
      if (key == "MemAvailable:") {
        s.memory_available_bytes = kib * 1024;
        break;
      }
  }
  s.clock = ChronyClockOffset(kStatusClockMaxAge);
  return s;
}

nlohmann::json SystemStatusToJson(const SystemStatus& s) {
  nlohmann::json j = {{"machine", s.machine},
                      {"disk_free_bytes", s.disk_free_bytes},
                      {"cpu_temperature_c", nullptr},
                      {"throttled", nullptr},
                      {"memory_available_bytes", nullptr},
                      {"clock_offset_ms", nullptr},
                      {"clock_source", nullptr}};
  if (s.cpu_temperature_c) j["cpu_temperature_c"] = *s.cpu_temperature_c;
  if (s.throttled) j["throttled"] = *s.throttled;
  if (s.memory_available_bytes) j["memory_available_bytes"] = *s.memory_available_bytes;
  if (s.clock) {
    j["clock_offset_ms"] = s.clock->offset_ms;
    j["clock_source"] = s.clock->source;
  }
  return j;
}

}  // namespace lfcam
