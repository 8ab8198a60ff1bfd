#include "lfcam/calib/board.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"

namespace lfcam {

std::vector<Vec3> BoardSpec::corners() const {
  std::vector<Vec3> points;
  points.reserve(std::size_t(corner_count()));
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) points.push_back(corner(i, j));
  return points;
}

bool BoardSpec::black_at(double x, double y) const {
  const auto i = static_cast<long long>(std::floor(x / square_mm));
  const auto j = static_cast<long long>(std::floor(y / square_mm));
  return ((i + j) & 1) == 0;
}

std::string BoardSpec::spec() const { return fmt::format("{}x{}@{}", cols, rows, square_mm); }

namespace {

void CheckBoard(const BoardSpec& b, const std::string& where) {
  if (b.cols < 2 || b.rows < 2 || b.cols > 200 || b.rows > 200)
    throw Error(
        fmt::format("{}: {}x{} inner corners: each count must be 2..200", where, b.cols, b.rows));
  if ((b.cols + b.rows) % 2 == 0)
    throw Error(fmt::format(
        "{}: {}x{} inner corners: one count must be odd and the other even, or the board's "
        "orientation is ambiguous",
        where, b.cols, b.rows));
  if (!(b.square_mm >= 0.1 && b.square_mm <= 10000))
    throw Error(fmt::format("{}: square size {} mm must be 0.1..10000", where, b.square_mm));
}

}  // namespace

BoardSpec ParseBoardSpec(const std::string& text) {
  const std::string usage = fmt::format(
      "'{}' is not a chessboard COLSxROWS@MM (inner corners, square size in mm, "
      "for example 10x7@30)",
      text);
  const auto x = text.find('x');
  const auto at = text.find('@');
  if (x == std::string::npos || at == std::string::npos || at < x) throw Error(usage);
  BoardSpec b;
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  auto parse_int = [&](const char* first, const char* last, int& out) {
    const auto r = std::from_chars(first, last, out);
    if (r.ec != std::errc() || r.ptr != last || first == last) throw Error(usage);
  };
  parse_int(begin, begin + x, b.cols);
  parse_int(begin + x + 1, begin + at, b.rows);
  const auto r = std::from_chars(begin + at + 1, end, b.square_mm);
  if (r.ec != std::errc() || r.ptr != end || begin + at + 1 == end || !std::isfinite(b.square_mm))
    throw Error(usage);
  CheckBoard(b, fmt::format("board '{}'", text));
  return b;
}

nlohmann::json BoardToJson(const BoardSpec& b) {
  return {{"type", "chessboard"},
          {"spec", b.spec()},
          {"inner_corners", {b.cols, b.rows}},
          {"square_mm", b.square_mm}};
}

BoardSpec BoardFromJson(const nlohmann::json& j, const std::string& where) {
  const std::string type = JsonString(j, "type", where);
  if (type != "chessboard")
    throw Error(fmt::format("{}: board type '{}' is not supported (chessboard)", where, type));
  const auto& corners = JsonField(j, "inner_corners", where);
  if (!corners.is_array() || corners.size() != 2)
    throw Error(fmt::format("{}: inner_corners must be [cols, rows]", where));
  BoardSpec b;
  b.cols = int(JsonInteger(corners[0], "", 0, 1000, where + ": inner_corners"));
  b.rows = int(JsonInteger(corners[1], "", 0, 1000, where + ": inner_corners"));
  b.square_mm = JsonNumber(j, "square_mm", where);
  CheckBoard(b, where);
  return b;
}

}  // namespace lfcam
