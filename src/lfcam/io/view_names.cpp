#include "lfcam/io/view_names.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam {

namespace {

namespace fs = std::filesystem;

std::optional<double> Number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

// The fields of `text` between the `separator`s (one field when there is none).
std::vector<std::string> Fields(const std::string& text, char separator) {
  std::vector<std::string> fields;
  for (std::size_t start = 0;;) {
    const auto at = text.find(separator, start);
    fields.push_back(text.substr(start, at - start));
    if (at == std::string::npos) return fields;
    start = at + 1;
  }
}

std::optional<int> Index(const std::string& text) {
  if (text.empty() || text.size() > 4 || !std::all_of(text.begin(), text.end(), ::isdigit))
    return std::nullopt;
  return std::stoi(text);
}

// An index with its axis' tag before it ("r05", "col5", "x12"): the tag in lower case and the
// index; nothing when `text` is not a tag of 1 to 3 letters followed by an index.
std::optional<std::pair<std::string, int>> TaggedIndex(const std::string& text) {
  std::size_t letters = 0;
  while (letters < text.size() && std::isalpha(static_cast<unsigned char>(text[letters])))
    ++letters;
  if (letters == 0 || letters > 3) return std::nullopt;
  const auto index = Index(text.substr(letters));
  if (!index) return std::nullopt;
  std::string tag = text.substr(0, letters);
  for (char& c : tag) c = char(std::tolower(static_cast<unsigned char>(c)));
  return std::pair{tag, *index};
}

// The row and column of two tagged indices, in either order: r/c, row/col, y/x, v/u (u being
// the horizontal angular coordinate, as light fields name it). Other tags are not indices.
std::optional<std::pair<int, int>> RowAndColumn(const std::pair<std::string, int>& a,
                                                const std::pair<std::string, int>& b) {
  static const std::array<std::pair<const char*, const char*>, 4> kPairs = {
      {{"r", "c"}, {"row", "col"}, {"y", "x"}, {"v", "u"}}};
  for (const auto& [row, col] : kPairs) {
    if (a.first == row && b.first == col) return std::pair{a.second, b.second};
    if (a.first == col && b.first == row) return std::pair{b.second, a.second};
  }
  return std::nullopt;
}

// "r05c07": two tagged indices in one field.
std::optional<std::pair<int, int>> JoinedRowAndColumn(const std::string& text) {
  for (std::size_t at = 2; at + 1 < text.size(); ++at) {
    if (!std::isdigit(static_cast<unsigned char>(text[at - 1])) ||
        !std::isalpha(static_cast<unsigned char>(text[at])))
      continue;
    const auto a = TaggedIndex(text.substr(0, at)), b = TaggedIndex(text.substr(at));
    if (a && b) return RowAndColumn(*a, *b);
    return std::nullopt;
  }
  return std::nullopt;
}

// Where a name that carries positions has its row index (the column index next, then the
// positions): Blender's NAME_RR_CC_Y_X_F_W, Stanford's NAME_RR_CC_Y_X[_]; nullopt for other
// namings and names with too few fields.
std::optional<std::size_t> RowIndexField(const std::vector<std::string>& parts, GridNaming naming) {
  if (naming == GridNaming::kBlender) {
    if (parts.size() >= 7) return parts.size() - 6;
  } else if (naming == GridNaming::kStanford) {
    const std::size_t skip = !parts.empty() && parts.back().empty() ? 1 : 0;  // a trailing '_'
    if (parts.size() >= 5 + skip) return parts.size() - 4 - skip;
  }
  return std::nullopt;
}

}  // namespace

std::optional<NamedView> ParseViewName(const std::string& file, GridNaming naming) {
  std::string stem = fs::path(file).stem().string();
  const std::vector<std::string> parts = Fields(stem, '_');
  NamedView v;
  v.file = file;
  switch (naming) {
    case GridNaming::kBlender:
      if (const auto at = RowIndexField(parts, naming)) {
        const std::string* t = parts.data() + *at;
        const auto rr = Index(t[0]), cc = Index(t[1]);
        const auto y = Number(t[2]), x = Number(t[3]), f = Number(t[4]), w = Number(t[5]);
        if (rr && cc && y && x && f && w && *f > 0 && *w > 0) {
          v.rr = *rr, v.cc = *cc, v.first = *y, v.second = *x, v.focal_mm = *f;
          v.sensor_width_mm = *w;
          return v;
        }
      }
      return std::nullopt;
    case GridNaming::kStanford:
      if (const auto at = RowIndexField(parts, naming)) {
        const std::string* t = parts.data() + *at;
        const auto rr = Index(t[0]), cc = Index(t[1]);
        const auto y = Number(t[2]), x = Number(t[3]);
        if (rr && cc && y && x) {
          v.rr = *rr, v.cc = *cc, v.first = *y, v.second = *x;
          return v;
        }
      }
      return std::nullopt;
    case GridNaming::kUnitGrid: {
      // [NAME_]RR_CC, or [NAME-]RR-CC where the name holds no '_' (beside a '_', a '-' is a
      // Stanford position's sign, and no index carries one).
      const std::vector<std::string> fields = parts.size() == 1 ? Fields(stem, '-') : parts;
      if (fields.size() >= 2 && (fields.size() == 2 || !fields.front().empty())) {
        const auto rr = Index(fields[fields.size() - 2]), cc = Index(fields.back());
        if (rr && cc) {
          v.rr = *rr, v.cc = *cc;
          return v;
        }
      }
      // The indices tagged with their axes: [NAME_]r05_c07, x07_y05, row5_col7, or r05c07.
      if (fields.size() >= 2) {
        const auto a = TaggedIndex(fields[fields.size() - 2]), b = TaggedIndex(fields.back());
        if (a && b)
          if (const auto rc = RowAndColumn(*a, *b)) {
            v.rr = rc->first, v.cc = rc->second;
            return v;
          }
      }
      if (const auto rc = JoinedRowAndColumn(fields.back())) {
        v.rr = rc->first, v.cc = rc->second;
        return v;
      }
      return std::nullopt;
    }
    case GridNaming::kSequence: {
      std::size_t digits = 0;
      while (digits < stem.size() &&
             std::isdigit(static_cast<unsigned char>(stem[stem.size() - 1 - digits])))
        ++digits;
      if (digits == 0 || digits > 6) return std::nullopt;
      v.rr = std::stoi(stem.substr(stem.size() - digits));
      return v;
    }
    case GridNaming::kHci:
      if (stem.size() > 9 && stem.starts_with("input_Cam")) {
        if (const auto index = Index(stem.substr(9))) {
          v.rr = *index;
          return v;
        }
      }
      return std::nullopt;
    case GridNaming::kDescription:
      return std::nullopt;
  }
  return std::nullopt;
}

std::string ToString(GridNaming naming) {
  switch (naming) {
    case GridNaming::kStanford:
      return "stanford";
    case GridNaming::kBlender:
      return "blender-grid";
    case GridNaming::kDescription:
      return "description";
    case GridNaming::kHci:
      return "hci";
    case GridNaming::kUnitGrid:
      return "unit-grid";
    case GridNaming::kSequence:
      return "sequence";
  }
  return "?";
}

GridNaming GridNamingFromString(const std::string& name) {
  for (const GridNaming n : {GridNaming::kStanford, GridNaming::kBlender, GridNaming::kHci,
                             GridNaming::kUnitGrid, GridNaming::kSequence})
    if (ToString(n) == name) return n;
  throw Error(fmt::format(
      "unknown naming '{}' (stanford, blender-grid, hci, unit-grid or sequence)", name));
}

std::optional<std::string> NameWithPositionsUnknown(const std::string& row_file,
                                                    const std::string& col_file,
                                                    GridNaming naming) {
  if (!ParseViewName(row_file, naming) || !ParseViewName(col_file, naming)) return std::nullopt;
  std::vector<std::string> fields = Fields(fs::path(row_file).stem().string(), '_');
  const std::vector<std::string> col_fields = Fields(fs::path(col_file).stem().string(), '_');
  const auto at = RowIndexField(fields, naming), col_at = RowIndexField(col_fields, naming);
  if (!at || !col_at) return std::nullopt;
  fields[*at + 1] = col_fields[*col_at + 1];
  fields[*at + 2] = fields[*at + 3] = "*";
  return fmt::format("{}{}", fmt::join(fields, "_"), fs::path(row_file).extension().string());
}

}  // namespace lfcam
