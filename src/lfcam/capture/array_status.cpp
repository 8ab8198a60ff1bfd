#include "lfcam/capture/array_status.h"

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>

#include "lfcam/capture/concurrency.h"
#include "lfcam/capture/node_client.h"
#include "lfcam/core/contact_sheet.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/json_input.h"
#include "lfcam/session/session.h"

namespace lfcam {

namespace {

constexpr double kHotCelsius = 80.0;

// What stops a node from capturing, and what is only worth a look, from its status.
void CheckStatus(const ArrayConfig& array, NodeReport& r) {
  const nlohmann::json& s = r.status;
  try {
    const auto& camera = JsonField(s, "camera", "status");
    if (!JsonField(camera, "present", "camera").get<bool>())
      r.problems.push_back(fmt::format("no camera: {}", camera.value("detail", "")));
    if (!JsonField(s, "configured", "status").get<bool>()) {
      r.problems.push_back("not configured");
    } else {
      const auto diffs = SettingsDifferences(
          SettingsFromJson(JsonField(s, "settings", "status"), "settings"), array.settings);
      if (!diffs.empty())
        r.problems.push_back(fmt::format("settings differ: {}", fmt::join(diffs, ", ")));
    }
    const auto& system = JsonField(s, "system", "status");
    if (system["clock_offset_ms"].is_number() &&
        std::abs(system["clock_offset_ms"].get<double>()) > array.max_clock_offset_ms)
      r.problems.push_back(fmt::format(
          "clock offset {:.1f} ms ({}) exceeds {:.1f} ms", system["clock_offset_ms"].get<double>(),
          system.value("clock_source", "?"), array.max_clock_offset_ms));
    else if (r.host_clock_offset_ms &&
             std::abs(*r.host_clock_offset_ms) > array.max_clock_offset_ms + r.round_trip_ms / 2)
      r.problems.push_back(
          fmt::format("clock offset {:.1f} ms (measured by the host) exceeds "
                      "{:.1f} ms",
                      *r.host_clock_offset_ms, array.max_clock_offset_ms));
    const auto free = JsonUnsigned(system, "disk_free_bytes", UINT64_MAX, "system");
    const auto needed = JsonUnsigned(s, "min_free_bytes", UINT64_MAX, "status");
    if (free < needed)
      r.problems.push_back(fmt::format("disk nearly full ({:.0f} MB free)", double(free) / 1e6));
    if (system["cpu_temperature_c"].is_number() &&
        system["cpu_temperature_c"].get<double>() >= kHotCelsius)
      r.warnings.push_back(
          fmt::format("hot: {:.0f} °C", system["cpu_temperature_c"].get<double>()));
    if (system["throttled"].is_string() && system["throttled"].get<std::string>() != "0x0")
      r.warnings.push_back(fmt::format("throttled: {}", system["throttled"].get<std::string>()));
  } catch (const Error& e) {
    r.problems.push_back(fmt::format("unreadable status: {}", e.what()));
  }
}

NodeReport AskStatus(const ArrayConfig& array, const SharedKey& key, const ArrayNode& node) {
  NodeReport r;
  r.row = node.row;
  r.col = node.col;
  r.address = node.address;
  try {
    NodeClient client(node.address, key, {2.0, 5.0});
    const TimedReply reply = client.Get("/v1/status");
    r.reachable = true;
    r.status = reply.body;
    r.round_trip_ms = double(reply.received_unix_ns - reply.sent_unix_ns) / 1e6;
    if (reply.body.contains("node_time_unix_ns") && reply.body["node_time_unix_ns"].is_number())
      r.host_clock_offset_ms = (reply.body["node_time_unix_ns"].get<double>() -
                                0.5 * double(reply.sent_unix_ns + reply.received_unix_ns)) /
                               1e6;
    CheckStatus(array, r);
  } catch (const NodeError& e) {
    r.reachable = e.reason() != "unreachable";
    r.problems.push_back(e.reason() == "unauthorized"
                             ? fmt::format("unauthorized (another key?): {}", e.what())
                             : e.what());
  }
  return r;
}

}  // namespace

std::vector<NodeReport> ArrayStatus(const ArrayConfig& array, const SharedKey& key) {
  std::vector<NodeReport> reports(array.nodes.size());
  RunConcurrently(array.nodes.size(), kMaxRequestThreads,
                  [&](std::size_t i) { reports[i] = AskStatus(array, key, array.nodes[i]); });
  return reports;
}

std::vector<NodeReport> ConfigureArray(const ArrayConfig& array, const SharedKey& key) {
  std::vector<std::string> failures(array.nodes.size());
  RunConcurrently(array.nodes.size(), kMaxRequestThreads, [&](std::size_t i) {
    try {
      NodeClient client(array.nodes[i].address, key, {2.0, 30.0});
      client.Post("/v1/configure", SettingsToJson(array.settings));
    } catch (const NodeError& e) {
      failures[i] = e.what();
    }
  });
  std::vector<NodeReport> reports = ArrayStatus(array, key);
  for (std::size_t i = 0; i < reports.size(); ++i)
    if (!failures[i].empty() && reports[i].problems.empty())
      reports[i].problems.push_back("configure failed: " + failures[i]);
  return reports;
}

nlohmann::json ReportsToJson(const std::vector<NodeReport>& reports) {
  nlohmann::json nodes = nlohmann::json::array();
  int ready = 0;
  for (const NodeReport& r : reports) {
    ready += r.ready();
    nlohmann::json n = {{"row", r.row},
                        {"col", r.col},
                        {"address", r.address},
                        {"reachable", r.reachable},
                        {"ready", r.ready()},
                        {"problems", r.problems},
                        {"warnings", r.warnings},
                        {"round_trip_ms", r.round_trip_ms},
                        {"host_clock_offset_ms", nullptr},
                        {"status", r.status}};
    if (r.host_clock_offset_ms) n["host_clock_offset_ms"] = *r.host_clock_offset_ms;
    nodes.push_back(std::move(n));
  }
  return {{"nodes", nodes}, {"ready", ready}, {"total", reports.size()}};
}

std::string ReportsTable(const std::vector<NodeReport>& reports, bool color) {
  const char* red = color ? "\033[31m" : "";
  const char* yellow = color ? "\033[33m" : "";
  const char* reset = color ? "\033[0m" : "";
  std::string out =
      fmt::format("{:<9} {:<22} {:<8} {:>6} {:>9} {:>8} {:>6} {:>5}  {}\n", "camera", "address",
                  "backend", "temp", "clock ms", "free GB", "held", "rtt", "problems");
  int ready = 0;
  for (const NodeReport& r : reports) {
    ready += r.ready();
    std::string backend = "-", temp = "-", clock = "-", free = "-", held = "-";
    if (r.status.is_object()) {
      backend = r.status.value("backend", "?");
      const auto& sys = r.status.value("system", nlohmann::json::object());
      if (sys.contains("cpu_temperature_c") && sys["cpu_temperature_c"].is_number())
        temp = fmt::format("{:.0f}°C", sys["cpu_temperature_c"].get<double>());
      if (sys.contains("clock_offset_ms") && sys["clock_offset_ms"].is_number())
        clock = fmt::format("{:+.2f}", sys["clock_offset_ms"].get<double>());
      else if (r.host_clock_offset_ms)
        clock = fmt::format("~{:+.1f}", *r.host_clock_offset_ms);
      if (sys.contains("disk_free_bytes") && sys["disk_free_bytes"].is_number())
        free = fmt::format("{:.1f}", sys["disk_free_bytes"].get<double>() / 1e9);
      held = std::to_string(r.status.value("captures_held", 0));
    }
    std::string notes;
    if (!r.problems.empty())
      notes += fmt::format("{}{}{}", red, fmt::join(r.problems, "; "), reset);
    if (!r.warnings.empty())
      notes += fmt::format("{}{}{}{}", notes.empty() ? "" : "; ", yellow,
                           fmt::join(r.warnings, "; "), reset);
    out += fmt::format("{:<9} {:<22} {:<8} {:>6} {:>9} {:>8} {:>6} {:>5.1f}  {}\n",
                       fmt::format("({},{})", r.row, r.col), r.address, backend, temp, clock, free,
                       held, r.round_trip_ms, notes.empty() ? "ok" : notes);
  }
  out += fmt::format("{} of {} nodes ready to capture\n", ready, reports.size());
  return out;
}

cv::Mat PreviewSheet(const ArrayConfig& array, const SharedKey& key, int tile_width) {
  const int tile_height = tile_width * 3 / 4;
  std::vector<cv::Mat> tiles(std::size_t(array.rows * array.cols));
  std::vector<std::string> labels(tiles.size());
  RunConcurrently(array.nodes.size(), kMaxRequestThreads, [&](std::size_t i) {
    const ArrayNode& n = array.nodes[i];
    // Row 0 at the bottom, as seen from behind the array.
    const std::size_t slot = std::size_t((array.rows - 1 - n.row) * array.cols + n.col);
    labels[slot] = fmt::format("({},{})", n.row, n.col);
    try {
      NodeClient client(n.address, key, {2.0, 30.0});
      const std::string jpeg = client.GetBytes(fmt::format("/v1/preview?width={}", tile_width));
      const cv::Mat bgr = DecodeImageBytes(
          {reinterpret_cast<const std::uint8_t*>(jpeg.data()), jpeg.size()},
          fmt::format("node ({},{})'s preview", n.row, n.col), ImageDecodeMode::kColour8);
      cv::cvtColor(bgr, tiles[slot], cv::COLOR_BGR2RGB);
    } catch (const Error& e) {
      labels[slot] += " " + std::string(e.what()).substr(0, 40);
    }
  });
  for (std::size_t s = 0; s < tiles.size(); ++s) {
    if (!tiles[s].empty()) continue;
    tiles[s] = cv::Mat(tile_height, tile_width, CV_8UC3, cv::Scalar(60, 60, 60));
    if (labels[s].empty())
      labels[s] =
          fmt::format("({},{}) no node", array.rows - 1 - int(s) / array.cols, int(s) % array.cols);
  }
  ContactSheetOptions options;
  options.columns = array.cols;
  options.tile_width = tile_width;
  options.title = fmt::format("preview {}x{}", array.rows, array.cols);
  return MakeContactSheet(tiles, labels, options);
}

}  // namespace lfcam
