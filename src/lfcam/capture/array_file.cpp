#include "lfcam/capture/array_file.h"

#include <fmt/format.h>

#include <set>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"

namespace lfcam {

namespace fs = std::filesystem;

const ArrayNode* ArrayConfig::node_at(int row, int col) const {
  for (const ArrayNode& n : nodes)
    if (n.row == row && n.col == col) return &n;
  return nullptr;
}

nlohmann::json ArrayToJson(const ArrayConfig& a) {
  nlohmann::json nodes = nlohmann::json::array();
  for (const ArrayNode& n : a.nodes)
    nodes.push_back({{"row", n.row}, {"col", n.col}, {"address", n.address}, {"group", n.group}});
  nlohmann::json j = {{"format", "lfcam-array"},
                      {"version", 1},
                      {"rows", a.rows},
                      {"cols", a.cols},
                      {"pitch_mm", a.pitch_mm},
                      {"key_file", a.key_file.string()},
                      {"max_clock_offset_ms", a.max_clock_offset_ms},
                      {"settings", SettingsToJson(a.settings)},
                      {"nodes", nodes}};
  if (a.intrinsics_board || a.world_board) {
    j["boards"] = nlohmann::json::object();
    if (a.intrinsics_board) j["boards"]["intrinsics"] = a.intrinsics_board->spec();
    if (a.world_board) j["boards"]["world"] = a.world_board->spec();
  }
  return j;
}

ArrayConfig ArrayFromJson(const nlohmann::json& j, const std::string& where) {
  JsonFormatVersion(j, "lfcam-array", 1, "array file", where);
  ArrayConfig a;
  a.rows = int(JsonInteger(j, "rows", 1, kMaxViewsPerSide, where));
  a.cols = int(JsonInteger(j, "cols", 1, kMaxViewsPerSide, where));
  a.pitch_mm = JsonNumber(j, "pitch_mm", where);
  if (!(a.pitch_mm > 0 && a.pitch_mm < 1e4))
    throw Error(fmt::format("{}: pitch_mm {} must be positive", where, a.pitch_mm));
  a.key_file = JsonString(j, "key_file", where);
  if (j.contains("max_clock_offset_ms")) {
    a.max_clock_offset_ms = JsonNumber(j, "max_clock_offset_ms", where);
    if (!(a.max_clock_offset_ms > 0))
      throw Error(fmt::format("{}: max_clock_offset_ms must be positive", where));
  }
  if (j.contains("settings")) a.settings = SettingsFromJson(j["settings"], where + ": settings");
  if (j.contains("boards")) {
    const auto& boards = j["boards"];
    auto board = [&](const char* key) -> std::optional<BoardSpec> {
      if (!boards.contains(key)) return std::nullopt;
      const std::string spec = JsonString(boards, key, where + ": boards");
      try {
        return ParseBoardSpec(spec);
      } catch (const Error& e) {
        throw Error(fmt::format("{}: boards: {}: {}", where, key, e.what()));
      }
    };
    if (!boards.is_object()) throw Error(fmt::format("{}: boards must be an object", where));
    a.intrinsics_board = board("intrinsics");
    a.world_board = board("world");
  }
  const auto& nodes = JsonField(j, "nodes", where);
  if (!nodes.is_array()) throw Error(fmt::format("{}: nodes must be an array", where));
  std::set<std::pair<int, int>> seen;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::string nw = fmt::format("{}: nodes[{}]", where, i);
    ArrayNode n;
    n.row = int(JsonInteger(nodes[i], "row", 0, a.rows - 1, nw));
    n.col = int(JsonInteger(nodes[i], "col", 0, a.cols - 1, nw));
    n.address = JsonString(nodes[i], "address", nw);
    const auto colon = n.address.rfind(':');
    if (n.address.empty() || n.address.size() > 255 || colon == std::string::npos || colon == 0 ||
        colon + 1 == n.address.size() ||
        n.address.find_first_not_of("0123456789", colon + 1) != std::string::npos)
      throw Error(fmt::format("{}: address '{}' must be HOST:PORT", nw, n.address));
    if (nodes[i].contains("group")) n.group = int(JsonInteger(nodes[i], "group", 0, 99, nw));
    if (!seen.insert({n.row, n.col}).second)
      throw Error(fmt::format("{}: ({}, {}) appears twice", nw, n.row, n.col));
    a.nodes.push_back(std::move(n));
  }
  return a;
}

ArrayConfig ReadArrayFile(const fs::path& path) {
  const auto bytes = ReadFileBytes(path, 1 << 20, "array file");
  return ArrayFromJson(
      ParseJsonBounded({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, path.string()),
      path.string());
}

fs::path KeyFilePath(const ArrayConfig& array, const fs::path& array_file) {
  return array.key_file.is_relative() ? array_file.parent_path() / array.key_file : array.key_file;
}

void WriteArrayFile(const fs::path& path, const ArrayConfig& array) {
  const std::string text = JsonToText(ArrayToJson(array), 2) + "\n";
  WriteFileAtomically(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

std::vector<ArrayNode> NodesFromPattern(int rows, int cols, const std::string& pattern) {
  std::vector<ArrayNode> nodes;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      std::string address;
      for (std::size_t i = 0; i < pattern.size();) {
        if (pattern[i] != '{') {
          address.push_back(pattern[i++]);
          continue;
        }
        const auto close = pattern.find('}', i);
        if (close == std::string::npos)
          throw UsageError(fmt::format("address pattern '{}': unclosed '{{'", pattern));
        const std::string key = pattern.substr(i + 1, close - i - 1);
        if (key == "row")
          address += std::to_string(r);
        else if (key == "col")
          address += std::to_string(c);
        else if (key == "row02")
          address += fmt::format("{:02d}", r);
        else if (key == "col02")
          address += fmt::format("{:02d}", c);
        else if (key == "index")
          address += std::to_string(r * cols + c);
        else if (key == "index1")
          address += std::to_string(r * cols + c + 1);
        else
          throw UsageError(
              fmt::format("address pattern '{}': unknown placeholder {{{}}} (row, "
                          "col, row02, col02, index, index1)",
                          pattern, key));
        i = close + 1;
      }
      nodes.push_back({r, c, address, 0});
    }
  return nodes;
}

}  // namespace lfcam
