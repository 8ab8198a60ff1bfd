#pragma once
// The whole array at a glance (`lfcam capture status`, `configure`, `preview`): every node asked
// at once, its answer checked against what the array needs to capture, and every problem named.
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/capture/array_file.h"
#include "lfcam/node/request_signature.h"

namespace lfcam {

struct NodeReport {
  int row = 0, col = 0;
  std::string address;
  bool reachable = false;
  nlohmann::json status;                       // the node's answer (null when unreachable)
  std::optional<double> host_clock_offset_ms;  // node clock minus host clock, from the round trip
  double round_trip_ms = 0;
  std::vector<std::string> problems;  // each stops the node from capturing
  std::vector<std::string> warnings;  // worth a look (hot, throttled)
  bool ready() const { return reachable && problems.empty(); }
};

// Asks every node of the array for its status, at once.
std::vector<NodeReport> ArrayStatus(const ArrayConfig& array, const SharedKey& key);

// Sends the array's settings to every node, then reads their status back.
std::vector<NodeReport> ConfigureArray(const ArrayConfig& array, const SharedKey& key);

nlohmann::json ReportsToJson(const std::vector<NodeReport>& reports);
// One line per node, problems marked; `color` wraps problems in ANSI red.
std::string ReportsTable(const std::vector<NodeReport>& reports, bool color);

// Every node's preview, laid out as the array is seen from behind (row 0 at the bottom), each
// labelled; an unreachable node is a grey tile with why.
cv::Mat PreviewSheet(const ArrayConfig& array, const SharedKey& key, int tile_width);

}  // namespace lfcam
