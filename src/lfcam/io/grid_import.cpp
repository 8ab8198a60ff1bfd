#include "lfcam/io/grid_import.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "lfcam/core/error.h"
#include "lfcam/core/image_header.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"

namespace lfcam {

namespace {

namespace fs = std::filesystem;

std::string LowerCaseExtension(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool IsImageName(const fs::path& p) {
  const std::string ext = LowerCaseExtension(p);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

// Image files a folder of views may hold that lfcam does not read (said, not silently passed).
bool IsUnreadImageName(const fs::path& p) {
  const std::string ext = LowerCaseExtension(p);
  for (const char* kind : {".tif", ".tiff", ".bmp", ".webp", ".ppm", ".pgm", ".exr", ".jp2"})
    if (ext == kind) return true;
  return false;
}

// The description file: {"format": "lfcam-views", "version": 1, "rows", "cols", "pitch_mm",
// "focal_px" or "focal_mm" and "sensor_width_mm", optional "st_distance_mm", and "views":
// [{"row", "col", "file", optional "x_mm", "y_mm"}] or "pattern": "view_{row}_{col}.png"}.
ImportedGrid ReadDescription(const fs::path& dir) {
  const fs::path path = dir / kViewsDescriptionName;
  const auto bytes = ReadFileBytes(path, 1 << 22, "views description");
  return GridFromDescription(
      ParseJsonBounded({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, path.string()),
      path.string());
}

}  // namespace

ImportedGrid GridFromDescription(const nlohmann::json& j, const std::string& where) {
  const auto version = JsonFormatVersion(j, "lfcam-views", 2, "views description", where);
  ImportedGrid g;
  g.naming = GridNaming::kDescription;
  // Version 2: a rectified rig (its zero-disparity plane, or each view's principal point).
  for (const char* key : {"rig", "zero_disparity_distance_mm"})
    if (j.contains(key) && version < 2)
      throw Error(fmt::format("{}: {} needs \"version\": 2", where, key));
  g.rows = int(JsonInteger(j, "rows", 1, kMaxViewsPerSide, where));
  g.cols = int(JsonInteger(j, "cols", 1, kMaxViewsPerSide, where));
  g.pitch_mm = JsonNumber(j, "pitch_mm", where);
  if (!(g.pitch_mm > 0)) throw Error(fmt::format("{}: pitch_mm must be positive", where));
  auto positive = [&](const char* key) -> std::optional<double> {
    if (!j.contains(key)) return std::nullopt;
    const double value = JsonNumber(j, key, where);
    if (!(value > 0)) throw Error(fmt::format("{}: {} must be positive", where, key));
    return value;
  };
  g.focal_px = positive("focal_px");
  g.focal_mm = positive("focal_mm");
  g.sensor_width_mm = positive("sensor_width_mm");
  g.st_distance_mm = positive("st_distance_mm");
  g.zero_disparity_mm = positive("zero_disparity_distance_mm");
  g.rig = g.zero_disparity_mm ? RigModel::kRectified : RigModel::kParallel;
  if (j.contains("rig")) {
    const std::string rig = JsonString(j, "rig", where);
    try {
      g.rig = RigModelFromString(rig);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: rig: {}", where, e.what()));
    }
    if (g.rig == RigModel::kParallel && g.zero_disparity_mm)
      throw Error(fmt::format(
          "{}: a parallel rig has no zero-disparity plane (zero_disparity_distance_mm)", where));
  }
  g.views.resize(std::size_t(g.rows * g.cols));
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      GridView& v = g.views[std::size_t(r * g.cols + c)];
      v.row = r, v.col = c;
      v.x_mm = (c - 0.5 * (g.cols - 1)) * g.pitch_mm;
      v.y_mm = (r - 0.5 * (g.rows - 1)) * g.pitch_mm;
    }
  if (j.contains("pattern")) {
    const std::string pattern = JsonString(j, "pattern", where);
    for (GridView& v : g.views) {
      std::string name = pattern;
      for (const auto& [key, value] :
           {std::pair<std::string, int>{"{row}", v.row}, {"{col}", v.col}}) {
        for (auto at = name.find(key); at != std::string::npos; at = name.find(key))
          name.replace(at, key.size(), std::to_string(value));
      }
      v.file = name;
    }
  } else {
    const auto& views = JsonField(j, "views", where);
    if (!views.is_array()) throw Error(fmt::format("{}: views must be an array", where));
    for (std::size_t i = 0; i < views.size(); ++i) {
      const std::string vw = fmt::format("{}: views[{}]", where, i);
      const int r = int(JsonInteger(views[i], "row", 0, g.rows - 1, vw));
      const int c = int(JsonInteger(views[i], "col", 0, g.cols - 1, vw));
      GridView& v = g.views[std::size_t(r * g.cols + c)];
      if (!v.file.empty()) throw Error(fmt::format("{}: ({}, {}) appears twice", vw, r, c));
      v.file = JsonString(views[i], "file", vw);
      if (views[i].contains("x_mm")) v.x_mm = JsonNumber(views[i], "x_mm", vw);
      if (views[i].contains("y_mm")) v.y_mm = JsonNumber(views[i], "y_mm", vw);
      if (views[i].contains("principal_point")) {
        if (version < 2) throw Error(fmt::format("{}: principal_point needs \"version\": 2", vw));
        const auto& pp = views[i]["principal_point"];
        const std::string at = vw + ": principal_point";
        if (!pp.is_array() || pp.size() != 2)
          throw Error(fmt::format("{}: must be [cx, cy] (pixels, OpenCV's)", at));
        v.principal_point = Vec2(JsonNumber(pp[0], "", at), JsonNumber(pp[1], "", at));
        if (v.principal_point->cwiseAbs().maxCoeff() > 1e6)
          throw Error(fmt::format("{}: far outside any image", at));
      }
    }
  }
  const auto with_pp = std::count_if(g.views.begin(), g.views.end(), [](const GridView& v) {
    return v.principal_point.has_value();
  });
  if (with_pp != 0 && with_pp != std::ptrdiff_t(g.views.size()))
    throw Error(
        fmt::format("{}: principal_point is given for {} of the {} views: give it for "
                    "every view or none",
                    where, with_pp, g.views.size()));
  if (with_pp != 0 && !j.contains("rig")) g.rig = RigModel::kRectified;
  for (const GridView& v : g.views) {
    const fs::path f(v.file);
    if (!v.file.empty() && (f.is_absolute() || v.file.find("..") != std::string::npos))
      throw Error(
          fmt::format("{}: view file '{}' must be a name inside the folder", where, v.file));
  }
  return g;
}

namespace {

// The grid that files named the position way (Blender, Stanford) form: its structure from the
// indices, its directions from the numbers. Nullopt with `why` set when they do not form one.
std::optional<ImportedGrid> GridFromPositions(const fs::path& dir, GridNaming naming,
                                              const std::vector<NamedView>& named,
                                              std::string* why) {
  ImportedGrid g;
  g.naming = naming;
  // The archive's columns in the order of their x, its rows in the order of their y = -first.
  std::map<int, std::pair<double, int>> col_x, row_y;  // index -> (sum, count)
  for (const NamedView& v : named) {
    col_x[v.cc].first += v.second, ++col_x[v.cc].second;
    row_y[v.rr].first -= v.first, ++row_y[v.rr].second;
  }
  auto order = [](const std::map<int, std::pair<double, int>>& m) {
    std::vector<std::pair<double, int>> sorted;
    for (const auto& [index, sum] : m) sorted.push_back({sum.first / sum.second, index});
    std::sort(sorted.begin(), sorted.end());
    std::map<int, int> rank;
    for (std::size_t i = 0; i < sorted.size(); ++i) rank[sorted[i].second] = int(i);
    return std::pair{rank, sorted};
  };
  const auto [col_rank, cols_sorted] = order(col_x);
  const auto [row_rank, rows_sorted] = order(row_y);
  g.cols = int(col_rank.size());
  g.rows = int(row_rank.size());
  double spacing = 0;
  int gaps = 0;
  for (std::size_t i = 1; i < cols_sorted.size(); ++i, ++gaps)
    spacing += cols_sorted[i].first - cols_sorted[i - 1].first;
  for (std::size_t i = 1; i < rows_sorted.size(); ++i, ++gaps)
    spacing += rows_sorted[i].first - rows_sorted[i - 1].first;
  g.pitch_mm = gaps > 0 ? spacing / gaps : 1.0;
  if (g.rows > kMaxViewsPerSide || g.cols > kMaxViewsPerSide) {
    *why = fmt::format("a grid of {}x{} views is larger than lfcam reads ({} a side)", g.rows,
                       g.cols, kMaxViewsPerSide);
    return std::nullopt;
  }
  g.views.resize(std::size_t(g.rows * g.cols));
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) g.views[std::size_t(r * g.cols + c)] = {r, c, "", 0, 0, {}};
  for (const NamedView& n : named) {
    GridView& v = g.views[std::size_t(row_rank.at(n.rr) * g.cols + col_rank.at(n.cc))];
    if (!v.file.empty()) {
      *why = fmt::format("{} names the same camera ({}_{}) as {}", n.file, n.rr, n.cc, v.file);
      return std::nullopt;
    }
    v.file = n.file;
    v.x_mm = n.second;
    v.y_mm = -n.first;
    if (n.focal_mm) {
      if (g.focal_mm && (std::abs(*g.focal_mm - *n.focal_mm) > 1e-9 ||
                         std::abs(*g.sensor_width_mm - *n.sensor_width_mm) > 1e-9))
        throw Error(
            fmt::format("{}: focal length {} mm and sensor {} mm differ from the other "
                        "views' ({} mm, {} mm): lfcam imports one camera model",
                        (dir / n.file).string(), *n.focal_mm, *n.sensor_width_mm, *g.focal_mm,
                        *g.sensor_width_mm));
      g.focal_mm = n.focal_mm;
      g.sensor_width_mm = n.sensor_width_mm;
    }
  }
  return g;
}

// The grid that files named by indices alone form (unit grid: RR, CC with row 1 at the top;
// HCI: NNN = row * cols + col from the top left): a regular grid of pitch 1 (unit) or the
// parameters' baseline. Nullopt with `why` set when they do not form one.
std::optional<ImportedGrid> GridFromIndices(GridNaming naming, const std::vector<NamedView>& named,
                                            const std::optional<HciParameters>& hci,
                                            const std::optional<GridShape>& shape,
                                            std::string* why) {
  ImportedGrid g;
  g.naming = naming;
  g.positions_known = false;
  std::vector<std::pair<int, int>> top_left;  // (row from the top, col from the left)
  if (naming == GridNaming::kHci || naming == GridNaming::kSequence) {
    int cols = 0, rows = 0;
    if (shape) {
      rows = shape->rows, cols = shape->cols;
      if (hci && hci->cams_x && (*hci->cams_x != cols || *hci->cams_y != rows)) {
        *why = fmt::format("a {}x{} grid disagrees with {}'s {}x{} (num_cams_y x num_cams_x)", rows,
                           cols, kHciParametersName, *hci->cams_y, *hci->cams_x);
        return std::nullopt;
      }
      // Holes are filled from their neighbours (--allow-missing), not made up: a grid at most
      // half empty.
      if (double(rows) * cols > 2.0 * double(named.size())) {
        *why = fmt::format(
            "a {}x{} grid holds {} cameras, and {} views are named: more than "
            "half of it would be missing",
            rows, cols, std::int64_t(rows) * cols, named.size());
        return std::nullopt;
      }
    } else if (hci && hci->cams_x) {
      cols = *hci->cams_x, rows = *hci->cams_y;
    } else {
      cols = rows = int(std::lround(std::sqrt(double(named.size()))));
      if (std::size_t(cols * rows) != named.size()) {
        *why = naming == GridNaming::kSequence
                   ? fmt::format(
                         "{} views are not a square grid, and numbered names say nothing "
                         "of its shape (--grid ROWSxCOLS says it)",
                         named.size())
                   : fmt::format(
                         "{} views are not a square grid, and {} to say its shape (--grid "
                         "ROWSxCOLS says it)",
                         named.size(),
                         hci ? fmt::format("{} gives no num_cams_x, num_cams_y", kHciParametersName)
                             : fmt::format("there is no {}", kHciParametersName));
        return std::nullopt;
      }
    }
    for (const NamedView& n : named) {
      if (n.rr >= rows * cols) {
        *why = fmt::format("{}: camera {} is outside the {}x{} grid", n.file, n.rr, rows, cols);
        return std::nullopt;
      }
      top_left.push_back({n.rr / cols, n.rr % cols});
    }
    g.rows = rows, g.cols = cols;
  } else {
    std::set<int> rrs, ccs;
    for (const NamedView& n : named) rrs.insert(n.rr), ccs.insert(n.cc);
    auto rank = [](const std::set<int>& set, int value) {
      return int(std::distance(set.begin(), set.find(value)));
    };
    for (const NamedView& n : named) top_left.push_back({rank(rrs, n.rr), rank(ccs, n.cc)});
    g.rows = int(rrs.size()), g.cols = int(ccs.size());
  }
  if (g.rows > kMaxViewsPerSide || g.cols > kMaxViewsPerSide) {
    *why = fmt::format("a grid of {}x{} views is larger than lfcam reads ({} a side)", g.rows,
                       g.cols, kMaxViewsPerSide);
    return std::nullopt;
  }
  g.pitch_mm = hci && hci->baseline_mm ? *hci->baseline_mm : 1.0;
  g.positions_known = hci && hci->baseline_mm;
  g.views.resize(std::size_t(g.rows * g.cols));
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c)
      g.views[std::size_t(r * g.cols + c)] = {
          r, c, "", (c - 0.5 * (g.cols - 1)) * g.pitch_mm, (r - 0.5 * (g.rows - 1)) * g.pitch_mm,
          {}};
  for (std::size_t i = 0; i < named.size(); ++i) {
    const int row = g.rows - 1 - top_left[i].first, col = top_left[i].second;
    GridView& v = g.views[std::size_t(row * g.cols + col)];
    if (!v.file.empty()) {
      *why = fmt::format("{} names the same camera as {}", named[i].file, v.file);
      return std::nullopt;
    }
    v.file = named[i].file;
  }
  if (hci) {
    g.focal_px = hci->focal_px();
    g.zero_disparity_mm = hci->focus_distance_mm;
  }
  return g;
}

// A numbered sequence's files: one name and extension before the numbers, the numbers one run
// without gaps (from any first number). Numbers them from 0 in `named` (rr), and returns why
// they are no sequence, empty when they are.
std::string NumberedInOrder(std::vector<NamedView>& named) {
  const auto prefix = [](const std::string& file) {
    const std::string stem = fs::path(file).stem().string();
    std::size_t end = stem.size();
    while (end > 0 && std::isdigit(static_cast<unsigned char>(stem[end - 1]))) --end;
    return stem.substr(0, end) + "*" + fs::path(file).extension().string();
  };
  const std::string first = prefix(named.front().file);
  std::set<int> numbers;
  for (const NamedView& n : named) {
    if (prefix(n.file) != first)
      return fmt::format("{} and {} are not named alike (one name, then the number)",
                         named.front().file, n.file);
    if (!numbers.insert(n.rr).second)
      return fmt::format("{}: its number is another file's too", n.file);
  }
  if (*numbers.rbegin() - *numbers.begin() + 1 != int(numbers.size()))
    return fmt::format("the numbers run from {} to {} with gaps ({} files)", *numbers.begin(),
                       *numbers.rbegin(), numbers.size());
  const int lowest = *numbers.begin();
  for (NamedView& n : named) n.rr -= lowest;
  return {};
}

// Names whose numbers run a row's and a column's index together (NAMERRCC, 0101.png ..
// 0909.png; no sequence, for the gaps): each number's digits split in two halves, the same
// number of digits in every name, forming a whole grid of at least 2 x 2. Sets each view's rr
// and cc and returns the digits an index takes; 0 where the names are not that.
int SplitJoinedIndices(std::vector<NamedView>& named) {
  int digits = -1;
  std::string name;  // what comes before the numbers, and the extension: alike in every file
  std::set<int> rows, cols;
  std::set<std::pair<int, int>> seen;
  std::vector<std::pair<int, int>> split;
  for (const NamedView& n : named) {
    const std::string stem = fs::path(n.file).stem().string();
    int run = 0;
    while (run < int(stem.size()) &&
           std::isdigit(static_cast<unsigned char>(stem[stem.size() - 1 - std::size_t(run)])))
      ++run;
    if (run % 2 != 0 || run < 2 || run > 6 || (digits >= 0 && run != digits)) return 0;
    const std::string before =
        stem.substr(0, stem.size() - std::size_t(run)) + fs::path(n.file).extension().string();
    if (digits >= 0 && before != name) return 0;
    digits = run;
    name = before;
    const std::string number = stem.substr(stem.size() - std::size_t(run));
    const int rr = std::stoi(number.substr(0, std::size_t(run / 2)));
    const int cc = std::stoi(number.substr(std::size_t(run / 2)));
    if (!seen.insert({rr, cc}).second) return 0;
    rows.insert(rr), cols.insert(cc);
    split.push_back({rr, cc});
  }
  if (rows.size() < 2 || cols.size() < 2 || rows.size() * cols.size() != named.size()) return 0;
  for (std::size_t i = 0; i < named.size(); ++i)
    named[i].rr = split[i].first, named[i].cc = split[i].second;
  return digits / 2;
}

std::optional<HciParameters> ReadHciParameters(const fs::path& dir) {
  std::error_code ec;
  const fs::path path = dir / kHciParametersName;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  const auto bytes = ReadFileBytes(path, 1 << 20, "HCI parameters");
  return ParseHciParameters({reinterpret_cast<const char*>(bytes.data()), bytes.size()},
                            path.string());
}

// The runs of digits in a file's name and what lies between them, in order.
std::vector<std::string> DigitRuns(const std::string& name) {
  std::vector<std::string> runs;
  for (std::size_t i = 0; i < name.size();) {
    const bool digit = std::isdigit(static_cast<unsigned char>(name[i])) != 0;
    std::size_t end = i;
    while (end < name.size() && (std::isdigit(static_cast<unsigned char>(name[end])) != 0) == digit)
      ++end;
    runs.push_back(name.substr(i, end - i));
    i = end;
  }
  return runs;
}

// The name a missing view would have, from the views beside it: `in_row` shares its row and
// `in_col` its column. For names that are indices alone (a unit grid's, the HCI benchmark's, a
// numbered sequence's), only a name that parses back to the hole's place (a unit grid:
// `in_row`'s row index and `in_col`'s column index; a number: `in_row`'s moved by the columns
// between them); for names that carry positions (Stanford's, Blender's), `in_row`'s name with
// `in_col`'s column index and each position, which only the missing file could say, a '*';
// nullopt otherwise.
std::optional<std::string> ExpectedViewName(const ImportedGrid& g, const GridView& hole,
                                            const GridView& in_row, const GridView& in_col) {
  if (g.joined_digits > 0) return std::nullopt;  // NAMERRCC: its numbers split by the folder
  const auto row_named = ParseViewName(in_row.file, g.naming);
  const auto col_named = ParseViewName(in_col.file, g.naming);
  if (!row_named || !col_named) return std::nullopt;
  if (g.naming == GridNaming::kStanford || g.naming == GridNaming::kBlender)
    return NameWithPositionsUnknown(in_row.file, in_col.file, g.naming);
  const std::vector<std::string> a = DigitRuns(in_row.file), b = DigitRuns(in_col.file);
  std::vector<std::string> candidates;
  if (g.naming == GridNaming::kUnitGrid) {
    // in_row's name with one run of digits taken from in_col's (its own padding).
    if (a.size() != b.size()) return std::nullopt;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i] == b[i] || !std::isdigit(static_cast<unsigned char>(a[i][0]))) continue;
      std::vector<std::string> x = a;
      x[i] = b[i];
      candidates.push_back(fmt::format("{}", fmt::join(x, "")));
    }
    for (const std::string& x : candidates)
      if (const auto n = ParseViewName(x, g.naming);
          n && n->rr == row_named->rr && n->cc == col_named->cc)
        return x;
    return std::nullopt;
  }
  if (g.naming != GridNaming::kHci && g.naming != GridNaming::kSequence) return std::nullopt;
  // One number, counted along the rows: in_row's, moved by the columns between them, written
  // as wide as in_row's (zero padded).
  const long number = long(row_named->rr) + (hole.col - in_row.col);
  if (number < 0) return std::nullopt;
  for (std::size_t i = a.size(); i-- > 0;) {
    if (!std::isdigit(static_cast<unsigned char>(a[i][0]))) continue;
    std::vector<std::string> x = a;
    x[i] = fmt::format("{:0{}}", number, a[i].size());
    const std::string name = fmt::format("{}", fmt::join(x, ""));
    if (const auto n = ParseViewName(name, g.naming); n && n->rr == number) return name;
    break;  // the number is the name's last run of digits
  }
  return std::nullopt;
}

// Where missing view `hole` lies among the views there: the nearest file in its row and in its
// column, "camera (r, c) lies in the row of A and the column of B", and the file's name where
// the names are indices alone ("camera (r, c) would be NAME: ...").
std::string WhereTheViewBelongs(const ImportedGrid& g, const GridView& hole) {
  const GridView* in_row = nullptr;
  const GridView* in_col = nullptr;
  for (const GridView& v : g.views) {
    if (v.file.empty()) continue;
    if (v.row == hole.row &&
        (!in_row || std::abs(v.col - hole.col) < std::abs(in_row->col - hole.col)))
      in_row = &v;
    if (v.col == hole.col &&
        (!in_col || std::abs(v.row - hole.row) < std::abs(in_col->row - hole.row)))
      in_col = &v;
  }
  std::vector<std::string> beside;
  if (in_row) beside.push_back(fmt::format("the row of {}", in_row->file));
  if (in_col) beside.push_back(fmt::format("the column of {}", in_col->file));
  if (beside.empty())
    return fmt::format("{}: no view in its row or column", CameraLabel(hole.row, hole.col));
  const std::optional<std::string> expected =
      in_row && in_col ? ExpectedViewName(g, hole, *in_row, *in_col) : std::nullopt;
  return fmt::format("{}{} lies in {}", CameraLabel(hole.row, hole.col),
                     expected ? fmt::format(" would be {}: it", *expected) : "",
                     fmt::join(beside, " and "));
}

ImportedGrid GridFromNames(const fs::path& dir, std::optional<GridNaming> forced,
                           const std::optional<GridShape>& shape) {
  std::vector<std::string> files;
  std::map<std::string, int> unread;  // images of kinds lfcam does not read, by extension
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (!entry.is_regular_file()) continue;
    if (IsImageName(entry.path()))
      files.push_back(entry.path().filename().string());
    else if (IsUnreadImageName(entry.path()))
      ++unread[LowerCaseExtension(entry.path())];
  }
  if (ec) throw Error(fmt::format("{}: cannot read the folder: {}", dir.string(), ec.message()));
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::vector<std::string> kinds;
    for (const auto& [ext, count] : unread) kinds.push_back(fmt::format("{} {}", count, ext));
    throw Error(fmt::format(
        "{}: no views (.png, .jpg) and no {}{}", dir.string(), kViewsDescriptionName,
        kinds.empty() ? ""
                      : fmt::format(" (its images are {} files, which lfcam does not read: "
                                    "convert them to PNG)",
                                    fmt::join(kinds, ", "))));
  }
  const std::optional<HciParameters> hci = ReadHciParameters(dir);

  // Every naming under which the names form a grid; the reason for each that does not.
  std::vector<ImportedGrid> fits;
  std::vector<std::string> reasons;
  // A numbered sequence is the least specific naming: tried only where no other fits.
  const std::vector<GridNaming> namings =
      forced
          ? std::vector<GridNaming>{*forced}
          : std::vector<GridNaming>{GridNaming::kBlender, GridNaming::kStanford, GridNaming::kHci,
                                    GridNaming::kUnitGrid, GridNaming::kSequence};
  for (const GridNaming naming : namings) {
    if (naming == GridNaming::kSequence && !forced && !fits.empty()) break;
    std::vector<NamedView> named;
    std::vector<std::string> ignored;
    std::string why;
    for (const std::string& f : files) {
      if (auto parsed = ParseViewName(f, naming)) {
        named.push_back(std::move(*parsed));
      } else if (naming == GridNaming::kHci && !f.starts_with("input_Cam")) {
        ignored.push_back(f);  // the benchmark's other images (masks, centre views)
      } else if (why.empty()) {
        why = fmt::format("{} does not parse", f);
      }
    }
    if (named.empty() && why.empty()) why = "no view is named that way";
    if (naming == GridNaming::kSequence && why.empty()) why = NumberedInOrder(named);
    std::optional<ImportedGrid> grid;
    // Not one sequence (gaps in the numbers: numbers without gaps are a sequence, whatever its
    // shape), but a row's and a column's index run together: a unit grid.
    if (naming == GridNaming::kSequence && !forced && !why.empty() && !named.empty() &&
        named.size() == files.size()) {
      std::vector<NamedView> split = named;
      if (const int digits = SplitJoinedIndices(split)) {
        std::string unused;
        grid = GridFromIndices(GridNaming::kUnitGrid, split, std::nullopt, std::nullopt, &unused);
        if (grid) {
          grid->joined_digits = digits;
          why.clear();
        }
      }
    }
    if (why.empty() && !grid)
      grid = naming == GridNaming::kHci || naming == GridNaming::kUnitGrid ||
                     naming == GridNaming::kSequence
                 ? GridFromIndices(naming, named, naming == GridNaming::kHci ? hci : std::nullopt,
                                   naming == GridNaming::kUnitGrid ? std::nullopt : shape, &why)
                 : GridFromPositions(dir, naming, named, &why);
    if (grid) {
      grid->ignored = std::move(ignored);
      grid->rig = DefaultRig(grid->naming);
      if (naming == GridNaming::kHci) grid->hci = hci;
      fits.push_back(std::move(*grid));
    } else {
      reasons.push_back(fmt::format("{}: {}", ToString(naming), why));
    }
  }
  if (fits.size() > 1) {
    std::vector<std::string> ways;
    for (const ImportedGrid& g : fits)
      ways.push_back(fmt::format("{} ({}x{} views)", ToString(g.naming), g.rows, g.cols));
    throw Error(
        fmt::format("{}: the names parse several ways: {}; say which with --naming, or "
                    "describe the folder in {} (docs/format.md)",
                    dir.string(), fmt::join(ways, ", "), kViewsDescriptionName));
  }
  if (fits.empty())
    throw Error(fmt::format(
        "{}: the names do not form a grid named the Stanford way (NAME_RR_CC_Y_X_), the Blender "
        "camera-grid way (NAME_RR_CC_Y_X_F_W), the HCI benchmark's (input_CamNNN), by indices "
        "(NAME_RR_CC, NAMERRCC, or tagged: NAME_rRR_cCC, xCC_yRR, vRR_uCC) or as one numbered "
        "sequence of a grid's views (NAMENNN: square, or --grid's): {}; "
        "describe the folder in {} instead (docs/format.md)",
        dir.string(), fmt::join(reasons, "; "), kViewsDescriptionName));
  return std::move(fits.front());
}

}  // namespace

std::vector<std::string> NamingNotes(const ImportedGrid& grid) {
  std::vector<std::string> notes;
  if (grid.joined_digits > 0)
    notes.push_back(fmt::format(
        "the numbers in the files' names read as a row's index and a column's run together, {} "
        "digits each (0102: row 1, column 2), rows from the top; the views' own parallax checks "
        "that order (axes)",
        grid.joined_digits));
  else if (grid.naming == GridNaming::kSequence)
    notes.push_back(fmt::format(
        "the views taken in the order of their files' numbers, row by row from the top left of a "
        "{}x{} grid (as the HCI benchmark numbers its cameras); the views' own parallax checks "
        "that order (axes)",
        grid.rows, grid.cols));
  if (grid.sixteen_bit)
    notes.push_back(
        "the views have 16 bits a channel: stored as 8 (sRGB, rounded), as every lfcam light "
        "field keeps its views; renders and exported views are 8-bit");
  if (grid.alpha)
    notes.push_back(
        "the views have an alpha channel: left out, each sample's colour taken as it is (not "
        "composited over any background)");
  if (grid.grey) notes.push_back("the views are grey: stored as colour with three equal channels");
  return notes;
}

std::string ToString(RigModel rig) { return rig == RigModel::kParallel ? "parallel" : "rectified"; }

RigModel RigModelFromString(const std::string& name) {
  if (name == "parallel") return RigModel::kParallel;
  if (name == "rectified") return RigModel::kRectified;
  throw Error(fmt::format("unknown rig '{}' (parallel or rectified)", name));
}

RigModel DefaultRig(GridNaming naming) {
  return naming == GridNaming::kBlender || naming == GridNaming::kDescription
             ? RigModel::kParallel
             : RigModel::kRectified;
}

namespace {

bool HoldsViews(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_regular_file(dir / kViewsDescriptionName, ec)) return true;
  int images = 0;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.is_regular_file(ec) && IsImageName(entry.path()) && ++images >= 2) return true;
  return false;
}

// The folders under `dir`, `levels` deep at most, that hold views, in name order.
void FoldersWithViews(const fs::path& dir, int levels, std::vector<fs::path>& found) {
  std::error_code ec;
  std::vector<fs::path> folders;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory(ec) && !name.starts_with(".") && name != "__MACOSX")
      folders.push_back(entry.path());
  }
  std::sort(folders.begin(), folders.end());
  for (const fs::path& folder : folders) {
    if (HoldsViews(folder))
      found.push_back(folder);
    else if (levels > 1)
      FoldersWithViews(folder, levels - 1, found);
  }
}

}  // namespace

std::optional<fs::path> ViewsSubfolder(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec) || HoldsViews(dir)) return std::nullopt;
  std::vector<fs::path> found;
  FoldersWithViews(dir, 2, found);
  if (found.empty()) return std::nullopt;
  if (found.size() == 1) return found.front();
  constexpr std::size_t kListed = 8;  // the rest counted, not listed
  std::vector<std::string> names;
  for (std::size_t i = 0; i < std::min(found.size(), kListed); ++i)
    names.push_back(fs::relative(found[i], dir, ec).string());
  throw Error(fmt::format(
      "{}: no views of its own, and {} folders in it hold views ({}{}): import one of them (a "
      "whole HCI benchmark: bench/hci_benchmark.py)",
      dir.string(), found.size(), fmt::join(names, ", "),
      found.size() > kListed ? fmt::format(" and {} more", found.size() - kListed) : ""));
}

ImportedGrid ScanGridFolder(const fs::path& dir, bool allow_missing,
                            std::optional<GridNaming> naming, std::optional<GridShape> shape) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(fmt::format("{}: not a folder", dir.string()));
  const bool described = fs::is_regular_file(dir / kViewsDescriptionName, ec);
  if (described && naming)
    throw Error(fmt::format("{}: described in {}: --naming does not apply", dir.string(),
                            kViewsDescriptionName));
  if (described && shape)
    throw Error(fmt::format("{}: described in {}: --grid does not apply", dir.string(),
                            kViewsDescriptionName));
  ImportedGrid g = described ? ReadDescription(dir) : GridFromNames(dir, naming, shape);
  if (shape && (g.rows != shape->rows || g.cols != shape->cols))
    throw Error(fmt::format("{}: the names ({}) give a {}x{} grid, not the {}x{} of --grid",
                            dir.string(), ToString(g.naming), g.rows, g.cols, shape->rows,
                            shape->cols));
  // Missing views: a file named but absent, or a grid position no file names.
  const GridView* first = nullptr;
  for (GridView& v : g.views) {
    if (!v.file.empty() && !fs::is_regular_file(dir / v.file, ec)) {
      if (g.naming != GridNaming::kDescription)
        throw Error(fmt::format("{}: not a file", (dir / v.file).string()));
      v.file.clear();
    }
    if (v.file.empty()) {
      g.missing.push_back(CameraLabel(v.row, v.col));
      continue;
    }
    const ImageHeader h = ProbeImageFile(dir / v.file);
    g.sixteen_bit = g.sixteen_bit || h.bits_per_channel > 8;
    g.alpha = g.alpha || h.channels == 2 || h.channels == 4;
    g.grey = (first == nullptr || g.grey) && h.channels <= 2;
    if (!first) {
      first = &v;
      g.width = h.width;
      g.height = h.height;
    } else if (h.width != g.width || h.height != g.height) {
      throw Error(fmt::format("{}: {}x{}, but {} is {}x{}: every view must have one size",
                              (dir / v.file).string(), h.width, h.height, first->file, g.width,
                              g.height));
    }
  }
  if (!first) throw Error(fmt::format("{}: none of the views is there", dir.string()));
  if (!g.missing.empty() && !allow_missing) {
    constexpr std::size_t kListed = 12;  // the rest counted, not listed
    const std::size_t listed = std::min(g.missing.size(), kListed);
    const std::string which =
        fmt::format(
            "{}", fmt::join(g.missing.begin(), g.missing.begin() + std::ptrdiff_t(listed), ", ")) +
        (g.missing.size() > listed ? fmt::format(" and {} more", g.missing.size() - listed) : "");
    // A few holes are placed by the files beside them, in the folder's own names (lfcam counts
    // rows from the bottom, which a folder's names need not).
    std::vector<std::string> placed;
    if (g.missing.size() <= 3)
      for (const GridView& v : g.views)
        if (v.file.empty()) placed.push_back(WhereTheViewBelongs(g, v));
    throw Error(fmt::format(
        "{}: the {}x{} grid is incomplete: {} {} missing, {} of its {} views here "
        "({}--allow-missing fills {} from {} neighbours)",
        dir.string(), g.rows, g.cols, which, g.missing.size() == 1 ? "is" : "are",
        g.views.size() - g.missing.size(), g.views.size(),
        placed.empty() ? "" : fmt::format("{}; ", fmt::join(placed, "; ")),
        g.missing.size() == 1 ? "it" : "them", g.missing.size() == 1 ? "its" : "their"));
  }
  return g;
}

}  // namespace lfcam
