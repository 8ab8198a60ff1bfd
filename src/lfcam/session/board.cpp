#include "lfcam/session/board.h"

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

std::string BoardSpec::spec() const {
  if (charuco())
    return fmt::format("charuco:{}x{}@{}/{}:{}", cols + 1, rows + 1, square_mm, marker_mm,
                       dictionary);
  return fmt::format("{}x{}@{}", cols, rows, square_mm);
}

namespace {

// The markers in one of OpenCV's predefined ArUco dictionaries "NxN_COUNT" (N 4..7, COUNT 50,
// 100, 250 or 1000), or 0 when `name` is not one.
int DictionarySize(const std::string& name) {
  for (int bits = 4; bits <= 7; ++bits)
    for (int count : {50, 100, 250, 1000})
      if (name == fmt::format("{}X{}_{}", bits, bits, count)) return count;
  return 0;
}

void CheckCharuco(const BoardSpec& b, const std::string& where) {
  if (b.cols < 2 || b.rows < 2 || b.cols > 200 || b.rows > 200)
    throw Error(
        fmt::format("{}: {}x{} squares: each count must be 3..201", where, b.cols + 1, b.rows + 1));
  if (!(b.square_mm >= 0.1 && b.square_mm <= 10000))
    throw Error(fmt::format("{}: square size {} mm must be 0.1..10000", where, b.square_mm));
  if (!(b.marker_mm >= 0.3 * b.square_mm && b.marker_mm <= 0.9 * b.square_mm))
    throw Error(fmt::format(
        "{}: marker size {} mm must be 0.3..0.9 of the square ({} mm), or the markers cannot be "
        "read or the corners cannot be found",
        where, b.marker_mm, b.square_mm));
  const int size = DictionarySize(b.dictionary);
  if (size == 0)
    throw Error(fmt::format(
        "{}: '{}' is not one of OpenCV's ArUco dictionaries (4X4_50 ... 7X7_1000: 4 to 7 bits a "
        "side, 50, 100, 250 or 1000 markers)",
        where, b.dictionary));
  const long long markers = (long long)(b.cols + 1) * (b.rows + 1) / 2;
  if (markers > size)
    throw Error(fmt::format("{}: {}x{} squares need {} markers; dictionary {} has {}", where,
                            b.cols + 1, b.rows + 1, markers, b.dictionary, size));
}

void CheckBoard(const BoardSpec& b, const std::string& where) {
  if (b.charuco()) return CheckCharuco(b, where);
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
  constexpr std::string_view kCharuco = "charuco:";
  const bool charuco = text.starts_with(kCharuco);
  const std::string usage =
      charuco ? fmt::format(
                    "'{}' is not a ChArUco board charuco:SXxSY@SQUARE/MARKER[:DICTIONARY] "
                    "(squares, square and marker sizes in mm, for example charuco:11x9@30/22)",
                    text)
              : fmt::format(
                    "'{}' is not a chessboard COLSxROWS@MM (inner corners, square size in mm, "
                    "for example 10x7@30) or a ChArUco board charuco:SXxSY@SQUARE/MARKER",
                    text);
  std::string body = charuco ? text.substr(kCharuco.size()) : text;
  BoardSpec b;
  if (charuco) {
    b.kind = BoardKind::kCharuco;
    b.dictionary = "5X5_100";
    if (const auto colon = body.find(':'); colon != std::string::npos) {
      b.dictionary = body.substr(colon + 1);
      for (char& c : b.dictionary) c = c == 'x' ? 'X' : c;
      body.resize(colon);
    }
  }
  const auto x = body.find('x');
  const auto at = body.find('@');
  const auto slash = charuco ? body.find('/') : body.size();
  if (x == std::string::npos || at == std::string::npos || at < x || slash == std::string::npos ||
      slash < at)
    throw Error(usage);
  const char* begin = body.data();
  auto parse_int = [&](const char* first, const char* last, int& out) {
    const auto r = std::from_chars(first, last, out);
    if (r.ec != std::errc() || r.ptr != last || first == last) throw Error(usage);
  };
  auto parse_number = [&](const char* first, const char* last, double& out) {
    const auto r = std::from_chars(first, last, out);
    if (r.ec != std::errc() || r.ptr != last || first == last || !std::isfinite(out))
      throw Error(usage);
  };
  parse_int(begin, begin + x, b.cols);
  parse_int(begin + x + 1, begin + at, b.rows);
  parse_number(begin + at + 1, begin + slash, b.square_mm);
  if (charuco) {
    parse_number(begin + slash + 1, begin + body.size(), b.marker_mm);
    b.cols -= 1;  // squares to inner corners
    b.rows -= 1;
  }
  CheckBoard(b, fmt::format("board '{}'", text));
  return b;
}

nlohmann::json BoardToJson(const BoardSpec& b) {
  if (b.charuco())
    return {{"type", "charuco"},
            {"spec", b.spec()},
            {"squares", {b.cols + 1, b.rows + 1}},
            {"square_mm", b.square_mm},
            {"marker_mm", b.marker_mm},
            {"dictionary", b.dictionary}};
  return {{"type", "chessboard"},
          {"spec", b.spec()},
          {"inner_corners", {b.cols, b.rows}},
          {"square_mm", b.square_mm}};
}

BoardSpec BoardFromJson(const nlohmann::json& j, const std::string& where) {
  const std::string type = JsonString(j, "type", where);
  if (type == "charuco") {
    const auto& squares = JsonField(j, "squares", where);
    if (!squares.is_array() || squares.size() != 2)
      throw Error(fmt::format("{}: squares must be [squares_x, squares_y]", where));
    BoardSpec b;
    b.kind = BoardKind::kCharuco;
    b.cols = int(JsonInteger(squares[0], "", 0, 1000, where + ": squares")) - 1;
    b.rows = int(JsonInteger(squares[1], "", 0, 1000, where + ": squares")) - 1;
    b.square_mm = JsonNumber(j, "square_mm", where);
    b.marker_mm = JsonNumber(j, "marker_mm", where);
    b.dictionary = JsonString(j, "dictionary", where);
    CheckBoard(b, where);
    return b;
  }
  if (type != "chessboard")
    throw Error(
        fmt::format("{}: board type '{}' is not supported (chessboard, charuco)", where, type));
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
