#include "lfcam/io/grid_import.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
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

bool IsImageName(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

std::optional<double> Number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::optional<int> Index(const std::string& text) {
  if (text.empty() || text.size() > 4 || !std::all_of(text.begin(), text.end(), ::isdigit))
    return std::nullopt;
  return std::stoi(text);
}

}  // namespace

std::optional<std::pair<GridNaming, NamedView>> ParseViewName(const std::string& file) {
  std::string stem = fs::path(file).stem().string();
  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    const auto underscore = stem.find('_', start);
    parts.push_back(stem.substr(start, underscore - start));
    if (underscore == std::string::npos) break;
    start = underscore + 1;
  }
  auto tail = [&](std::size_t n, std::size_t skip) {
    return std::vector<std::string>(parts.end() - std::ptrdiff_t(n + skip),
                                    parts.end() - std::ptrdiff_t(skip));
  };
  NamedView v;
  v.file = file;
  if (parts.size() >= 7) {
    const auto t = tail(6, 0);
    const auto rr = Index(t[0]), cc = Index(t[1]);
    const auto y = Number(t[2]), x = Number(t[3]), f = Number(t[4]), w = Number(t[5]);
    if (rr && cc && y && x && f && w && *f > 0 && *w > 0) {
      v.rr = *rr, v.cc = *cc, v.first = *y, v.second = *x, v.focal_mm = *f, v.sensor_width_mm = *w;
      return std::pair{GridNaming::kBlender, v};
    }
  }
  const std::size_t skip = !parts.empty() && parts.back().empty() ? 1 : 0;  // a trailing '_'
  if (parts.size() >= 5 + skip) {
    const auto t = tail(4, skip);
    const auto rr = Index(t[0]), cc = Index(t[1]);
    const auto y = Number(t[2]), x = Number(t[3]);
    if (rr && cc && y && x) {
      v.rr = *rr, v.cc = *cc, v.first = *y, v.second = *x;
      return std::pair{GridNaming::kStanford, v};
    }
  }
  return std::nullopt;
}

namespace {

ImageHeader HeaderOf(const fs::path& path) {
  InputFile in(path);
  std::vector<std::uint8_t> bytes(std::size_t(std::min<std::uint64_t>(in.size(), 1 << 18)));
  in.read_exactly(bytes.data(), bytes.size(), 0);
  try {
    return ProbeImageHeader(bytes);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", path.string(), e.what()));
  }
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
  JsonFormatVersion(j, "lfcam-views", 1, "views description", where);
  ImportedGrid g;
  g.naming = GridNaming::kDescription;
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
    }
  }
  for (const GridView& v : g.views) {
    const fs::path f(v.file);
    if (!v.file.empty() && (f.is_absolute() || v.file.find("..") != std::string::npos))
      throw Error(
          fmt::format("{}: view file '{}' must be a name inside the folder", where, v.file));
  }
  return g;
}

namespace {

ImportedGrid GridFromNames(const fs::path& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.is_regular_file() && IsImageName(entry.path()))
      files.push_back(entry.path().filename().string());
  if (ec) throw Error(fmt::format("{}: cannot read the folder: {}", dir.string(), ec.message()));
  std::sort(files.begin(), files.end());
  if (files.empty())
    throw Error(
        fmt::format("{}: no views (.png, .jpg) and no {}", dir.string(), kViewsDescriptionName));
  std::optional<GridNaming> naming;
  std::vector<NamedView> named;
  for (const std::string& f : files) {
    const auto parsed = ParseViewName(f);
    if (!parsed)
      throw Error(
          fmt::format("{}: the name does not parse as NAME_RR_CC_Y_X_ (Stanford) or "
                      "NAME_RR_CC_Y_X_F_W (Blender camera grid); describe the folder "
                      "in {} instead (docs/format.md)",
                      (dir / f).string(), kViewsDescriptionName));
    if (naming && *naming != parsed->first)
      throw Error(fmt::format("{}: named the {} way, but {} the {} way", (dir / f).string(),
                              ToString(parsed->first), named.front().file, ToString(*naming)));
    naming = parsed->first;
    named.push_back(parsed->second);
  }
  ImportedGrid g;
  g.naming = *naming;
  // The grid's structure from the indices, its directions from the numbers: the archive's
  // columns in the order of their x, its rows in the order of their y = -first.
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
  if (g.rows > kMaxViewsPerSide || g.cols > kMaxViewsPerSide)
    throw Error(fmt::format("{}: a grid of {}x{} views is larger than lfcam reads ({} a side)",
                            dir.string(), g.rows, g.cols, kMaxViewsPerSide));
  double spacing = 0;
  int gaps = 0;
  for (std::size_t i = 1; i < cols_sorted.size(); ++i, ++gaps)
    spacing += cols_sorted[i].first - cols_sorted[i - 1].first;
  for (std::size_t i = 1; i < rows_sorted.size(); ++i, ++gaps)
    spacing += rows_sorted[i].first - rows_sorted[i - 1].first;
  g.pitch_mm = gaps > 0 ? spacing / gaps : 1.0;
  g.views.resize(std::size_t(g.rows * g.cols));
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      GridView& v = g.views[std::size_t(r * g.cols + c)];
      v.row = r, v.col = c;
    }
  for (const NamedView& n : named) {
    GridView& v = g.views[std::size_t(row_rank.at(n.rr) * g.cols + col_rank.at(n.cc))];
    if (!v.file.empty())
      throw Error(fmt::format("{}: the same camera ({}_{}) as {}", (dir / n.file).string(), n.rr,
                              n.cc, v.file));
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

}  // namespace

std::string ToString(GridNaming naming) {
  switch (naming) {
    case GridNaming::kStanford:
      return "stanford";
    case GridNaming::kBlender:
      return "blender-grid";
    case GridNaming::kDescription:
      return "description";
  }
  return "?";
}

ImportedGrid ScanGridFolder(const fs::path& dir, bool allow_missing) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(fmt::format("{}: not a folder", dir.string()));
  ImportedGrid g = fs::is_regular_file(dir / kViewsDescriptionName, ec) ? ReadDescription(dir)
                                                                        : GridFromNames(dir);
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
    const ImageHeader h = HeaderOf(dir / v.file);
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
  if (!g.missing.empty() && !allow_missing)
    throw Error(
        fmt::format("{}: the {}x{} grid is incomplete: {} {} missing (--allow-missing "
                    "fills them from their neighbours)",
                    dir.string(), g.rows, g.cols, fmt::join(g.missing, ", "),
                    g.missing.size() == 1 ? "is" : "are"));
  return g;
}

double EstimateDominantDepthMm(const fs::path& dir, const ImportedGrid& g, double focal_px) {
  // The two outermost views of the middle row, else of the middle column.
  const bool along_row = g.cols >= g.rows;
  const GridView* a = nullptr;
  const GridView* b = nullptr;
  const int n = along_row ? g.cols : g.rows;
  for (int i = 0; i < n && !a; ++i) {
    const GridView& v = along_row ? g.view(g.rows / 2, i) : g.view(i, g.cols / 2);
    if (!v.file.empty()) a = &v;
  }
  for (int i = n - 1; i >= 0 && !b; --i) {
    const GridView& v = along_row ? g.view(g.rows / 2, i) : g.view(i, g.cols / 2);
    if (!v.file.empty()) b = &v;
  }
  if (!a || !b || a == b)
    throw Error(
        fmt::format("{}: one view: give the st-plane's distance (--st-distance)", dir.string()));
  cv::Mat ga, gb;
  ReadImageGray8(dir / a->file).convertTo(ga, CV_32F);
  ReadImageGray8(dir / b->file).convertTo(gb, CV_32F);
  cv::Mat window;
  cv::createHanningWindow(window, ga.size(), CV_32F);
  const cv::Point2d shift = cv::phaseCorrelate(ga, gb, window);
  const double baseline = std::hypot(b->x_mm - a->x_mm, b->y_mm - a->y_mm);
  const double disparity = std::hypot(shift.x, shift.y);
  if (disparity < 0.5 || baseline <= 0)
    throw Error(
        fmt::format("{}: the views show no measurable disparity ({:.2f} px between {} "
                    "and {}): give the st-plane's distance (--st-distance)",
                    dir.string(), disparity, a->file, b->file));
  return focal_px * baseline / disparity;
}

ImportedSession MakeImportedSession(const fs::path& dir, const ImportedGrid& g,
                                    const ImportOptions& o) {
  ImportedSession s;
  // The intrinsics: a focal length in pixels, from the flags, the description or the names.
  const auto focal_mm = o.focal_mm ? o.focal_mm : g.focal_mm;
  const auto sensor_mm = o.sensor_width_mm ? o.sensor_width_mm : g.sensor_width_mm;
  if (o.focal_px)
    s.focal_px = *o.focal_px;
  else if (g.focal_px && !o.focal_mm)
    s.focal_px = *g.focal_px;
  else if (focal_mm && sensor_mm)
    s.focal_px = *focal_mm / *sensor_mm * g.width;
  else
    throw Error(
        fmt::format("{}: the views' focal length is not known: give --focal-px, or "
                    "--focal-mm and --sensor-width-mm",
                    dir.string()));
  if (!(s.focal_px > 0)) throw Error("the focal length must be positive");

  if (o.st_distance_mm) {
    s.st_distance_mm = *o.st_distance_mm;
  } else if (g.st_distance_mm) {
    s.st_distance_mm = *g.st_distance_mm;
  } else {
    s.st_distance_mm = EstimateDominantDepthMm(dir, g, s.focal_px);
    s.st_distance_estimated = true;
  }
  if (!(s.st_distance_mm > 0)) throw Error("the st distance must be positive");
  const double d = s.st_distance_mm;

  // The camera plane at z = d, x right, y up; the grid's corner half a pitch beyond its
  // outermost cameras (the centres are where the names say: `build` reads each camera at its
  // own centre).
  double x_min = 1e300, y_min = 1e300, x_sum = 0, y_sum = 0;
  int present = 0;
  for (const GridView& v : g.views)
    if (!v.file.empty()) {
      x_min = std::min(x_min, v.x_mm - v.col * g.pitch_mm);
      y_min = std::min(y_min, v.y_mm - v.row * g.pitch_mm);
      x_sum += v.x_mm - v.col * g.pitch_mm;
      y_sum += v.y_mm - v.row * g.pitch_mm;
      ++present;
    }
  // The grid's origin (camera (0, 0)'s ideal centre): the mean over the views.
  const double x0 = x_sum / present, y0 = y_sum / present;
  (void)x_min, (void)y_min;
  Slab slab;
  slab.uv.p_ca = Vec3(x0 - 0.5 * g.pitch_mm, y0 - 0.5 * g.pitch_mm, d);
  slab.uv.u_ca = Vec3::UnitX();
  slab.uv.v_ca = Vec3::UnitY();
  slab.uv.n_ca = Vec3::UnitZ();
  slab.uv.rows = g.rows;
  slab.uv.cols = g.cols;
  slab.uv.pitch_mm = g.pitch_mm;
  // The st window: what the grid's central (ideal) camera sees on the plane z = 0.
  const Vec3 centre = slab.uv.center();
  slab.st.width_mm = d * g.width / s.focal_px;
  slab.st.height_mm = d * g.height / s.focal_px;
  slab.st.origin =
      Vec3(centre.x() - 0.5 * slab.st.width_mm, centre.y() - 0.5 * slab.st.height_mm, 0);
  slab.st.x_axis = Vec3::UnitX();
  slab.st.y_axis = Vec3::UnitY();
  slab.st_domain = {};
  slab.validate();

  CalibrationFile& cal = s.calibration;
  cal.rows = g.rows;
  cal.cols = g.cols;
  cal.width = g.width;
  cal.height = g.height;
  cal.slab = slab;
  const Mat3 rotation = WorldFromCameraRotation(slab.uv.u_ca, slab.uv.v_ca, slab.uv.n_ca);
  for (const GridView& v : g.views) {
    CalibratedCamera c;
    c.row = v.row;
    c.col = v.col;
    c.calibrated = !v.file.empty();
    if (!c.calibrated) c.reason = "not in the imported folder";
    c.intrinsics.width = g.width;
    c.intrinsics.height = g.height;
    c.intrinsics.fx = c.intrinsics.fy = s.focal_px;
    c.intrinsics.cx = 0.5 * (g.width - 1);
    c.intrinsics.cy = 0.5 * (g.height - 1);
    c.world_from_camera = {rotation, Vec3(v.x_mm, v.y_mm, d)};
    cal.cameras.push_back(std::move(c));
  }
  cal.summary = {{"import",
                  {{"naming", ToString(g.naming)},
                   {"folder", dir.string()},
                   {"focal_px", s.focal_px},
                   {"st_distance_mm", d},
                   {"st_distance_estimated", s.st_distance_estimated},
                   {"missing", g.missing}}}};

  CaptureManifest& m = s.manifest;
  m.rows = g.rows;
  m.cols = g.cols;
  m.pitch_mm = g.pitch_mm;
  m.sensor_width = g.width;
  m.sensor_height = g.height;
  m.sensor_model = "imported (" + ToString(g.naming) + ")";
  Shot scene(ShotKind::kScene, "scene");
  for (const GridView& v : g.views)
    if (!v.file.empty()) scene.images.push_back(ShotImage(v.row, v.col, v.file));
  m.shots.push_back(std::move(scene));
  m.source = cal.summary["import"];
  return s;
}

}  // namespace lfcam
