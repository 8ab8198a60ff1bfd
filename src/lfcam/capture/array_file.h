#pragma once
// The array file (docs/hardware.md): what the host knows of the camera array it drives, the
// grid and pitch, every node's address by (row, col), optional trigger groups, the settings
// locked on every node, the boards, and where the key is.
//
//   {"format": "lfcam-array", "version": 1, "rows": 10, "cols": 10, "pitch_mm": 28.0,
//    "key_file": "array.key", "max_clock_offset_ms": 5.0,
//    "settings": {"width": 2592, "height": 1944, "exposure_us": 20000, ...},
//    "boards": {"intrinsics": "10x7@30", "world": "11x10@50"},
//    "nodes": [{"row": 0, "col": 0, "address": "10.0.0.100:8470", "group": 0}, ...]}
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/node/capture_settings.h"
#include "lfcam/session/board.h"

namespace lfcam {

struct ArrayNode {
  int row = 0, col = 0;
  std::string address;  // HOST:PORT
  int group = 0;        // trigger group (shoot --groups staggers them)
};

struct ArrayConfig {
  int rows = 10, cols = 10;
  double pitch_mm = 28.0;
  std::filesystem::path key_file;  // absolute, or relative to the array file
  double max_clock_offset_ms = 5.0;
  CaptureSettings settings;
  std::optional<BoardSpec> intrinsics_board, world_board;
  std::vector<ArrayNode> nodes;

  const ArrayNode* node_at(int row, int col) const;
};

nlohmann::json ArrayToJson(const ArrayConfig& array);
ArrayConfig ArrayFromJson(const nlohmann::json& j, const std::string& where);
// Reads an array file. Throws lfcam::Error naming the file.
ArrayConfig ReadArrayFile(const std::filesystem::path& path);
// The key file of an array read from `array_file` (a relative key_file is relative to it).
std::filesystem::path KeyFilePath(const ArrayConfig& array,
                                  const std::filesystem::path& array_file);
void WriteArrayFile(const std::filesystem::path& path, const ArrayConfig& array);

// One node per grid position, addresses from a pattern with {row}, {col} (two digits: {row02},
// {col02}) and {index} (row * cols + col; {index1} from 1), e.g. "10.0.0.{index1}:8470".
// Throws lfcam::UsageError for an unknown placeholder.
std::vector<ArrayNode> NodesFromPattern(int rows, int cols, const std::string& pattern);

}  // namespace lfcam
