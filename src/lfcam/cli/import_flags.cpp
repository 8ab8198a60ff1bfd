#include "lfcam/cli/import_flags.h"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "lfcam/calib/lightfield_build.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"
#include "lfcam/depth/occlusion_order.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/io/lenslet_image.h"
#include "lfcam/io/parallax_axes.h"
#include "lfcam/io/parallel_import.h"
#include "lfcam/io/rectified_import.h"

namespace lfcam::cli {
namespace {

// Which file became which view (lfcam's grid: row 0 at the bottom).
nlohmann::json ViewFiles(const ImportedGrid& grid) {
  nlohmann::json views = nlohmann::json::array();
  for (const GridView& v : grid.views)
    views.push_back({{"row", v.row}, {"col", v.col}, {"file", v.file}});
  return views;
}

// The import's result with its summary: what every rig says (the grid, the views' files, the
// samples, the time, the views filled) and `rig_fields`, what this rig's geometry says.
ImportedLightField Imported(LightField lf, const ImportedGrid& grid, RigModel rig,
                            const std::vector<std::string>& filled, double seconds,
                            nlohmann::json rig_fields) {
  rig_fields.update({{"naming", ToString(grid.naming)},
                     {"rig", ToString(rig)},
                     {"rows", grid.rows},
                     {"cols", grid.cols},
                     {"view_width", grid.width},
                     {"view_height", grid.height},
                     {"n_s", lf.dims().n_s},
                     {"n_t", lf.dims().n_t},
                     {"filled", filled},
                     {"views", ViewFiles(grid)},
                     {"seconds", seconds}});
  return {std::move(lf), std::move(rig_fields), grid.ignored};
}

// A rectified rig: the views as they are, with the geometry said (and what was assumed).
ImportedLightField ImportRectified(const std::string& dir, const ImportedGrid& grid,
                                   const ImportOptions& o, bool quiet) {
  const RectifiedGeometry geometry = ResolveRectifiedGeometry(grid, o);
  ProgressBar progress("importing views", std::int64_t(grid.rows) * grid.cols,
                       ProgressWanted(quiet));
  const auto advance = progress.callback();
  RectifiedImportReport report;
  LightField lf = ImportRectifiedViews(
      dir, grid, geometry,
      [&] {
        if (advance) advance(1);
      },
      &report, o.fill_dark_views);
  progress.finish();
  return Imported(std::move(lf), grid, RigModel::kRectified, report.filled, report.seconds,
                  {{"pitch_mm", geometry.pitch_mm},
                   {"focal_px", geometry.focal_px},
                   {"st_distance_mm", geometry.zero_disparity_mm},
                   {"zero_disparity_distance_mm", geometry.zero_disparity_mm},
                   {"length_unit", geometry.metric ? "mm" : "units"},
                   {"st_distance_estimated", false},
                   {"assumed", geometry.assumed},
                   {"notes", geometry.notes},
                   {"dark", report.dark}});
}

// `said` as the import's first note: in its summary (the `note:` lines) and in the file's
// import.notes.
void SayFirst(ImportedLightField& imported, const std::string& said) {
  for (nlohmann::json* holder : {&imported.lightfield.metadata()["import"], &imported.summary}) {
    nlohmann::json& notes = (*holder)["notes"];
    if (!notes.is_array()) notes = nlohmann::json::array();
    notes.insert(notes.begin(), said);
  }
}

}  // namespace

void ImportFlags::AddTo(CLI::App& command) {
  command
      .add_option("--naming", naming,
                  "How the views are named: auto, stanford (NAME_RR_CC_Y_X_), blender-grid "
                  "(NAME_RR_CC_Y_X_F_W), hci (input_CamNNN.png + parameters.cfg), unit-grid "
                  "([NAME_]RR_CC: indices only, row 1 at the top; or tagged, r05_c07, x07_y05, "
                  "v5_u7; auto also reads NAMERRCC with gaps as one) or sequence (NAMENNN: one "
                  "square grid's views, or --grid's, numbered row by row from the top left, "
                  "tried only where no other naming fits); auto refuses names that parse "
                  "several ways")
      ->capture_default_str();
  command
      .add_option("--lenslet", lenslet,
                  "N: the views a side of a lenslet image (one image, ESLF: each N x N block "
                  "of pixels one microlens's samples of the aperture); default found from "
                  "its pixels, and said")
      ->check(CLI::Range(3, 64));
  command.add_option("--grid", grid_shape,
                     "ROWSxCOLS: the grid's shape, for views whose names do not give it (a "
                     "numbered sequence, NAMENNN, row by row from the top left; HCI views "
                     "without parameters.cfg): 1x101 for a row of 101 cameras");
  command
      .add_option("--rig", rig,
                  "auto, parallel (centred sensors: zero disparity at infinity) or rectified "
                  "(shifted sensors: zero disparity on one plane, the st-plane; views stored "
                  "sample for sample); auto: Blender grids parallel, the others rectified")
      ->capture_default_str();
  command.add_option("--st-distance", st_distance,
                     "Distance of the st-plane from the cameras, mm. Parallel rig: default the "
                     "description's, else the depth most of the scene lies at, estimated. "
                     "Rectified rig: the zero-disparity plane's (default the description's or "
                     "parameters.cfg's, else assumed and said)");
  command.add_option("--pitch-mm", pitch_mm,
                     "The cameras' spacing, for views named by indices alone (default 1, said)");
  st_res_ = command.add_option(
      "--st-res", st_res,
      "Parallel rig: st samples per view, N_SxN_T (default: the views' sample spacing "
      "over the st domain)");
  st_domain_ = command.add_option(
      "--st-domain", st_domain,
      "Parallel rig: sampled st domain S0,T0,S1,T1 (view-window units, [0, 1]^2 being what the "
      "central camera sees on the st-plane, the default)");
  st_windows_ =
      command
          .add_option("--st-windows", st_windows,
                      "Parallel rig: views (each view in its own window, the st domain's grid "
                      "moved to where its camera looks: its own pixels) or shared (every view "
                      "samples the st domain)")
          ->capture_default_str();
  command.add_option("--focal-px", focal_px, "The views' focal length in pixels");
  command.add_option("--focal-mm", focal_mm,
                     "The lens's focal length, mm (with --sensor-width-mm)");
  command.add_option("--sensor-width-mm", sensor_width_mm, "The sensor's width, mm");
  resampling_ = command
                    .add_option("--resampling", resampling,
                                "Parallel rig: linear, cubic or lanczos4 (as for build)")
                    ->capture_default_str();
  command.add_option("--chroma", chroma, "guided or interpolated, for JPEG views (as for build)")
      ->capture_default_str();
  command.add_flag("--allow-missing", allow_missing,
                   "Fill views missing from the grid from their nearest neighbours (recorded)");
  command.add_flag("--keep-dark-views", keep_dark_views,
                   "Keep views that recorded black, or nearly, as they are (by default they are "
                   "filled from their neighbours, as missing views are)");
  command.add_flag("--flip-rows", flip_rows,
                   "Take the grid's rows in reverse: for names whose row index or y counts the "
                   "other way than lfcam reads it (docs/format.md)");
  command.add_flag("--flip-cols", flip_cols,
                   "Take the grid's columns in reverse: for names whose column index or x counts "
                   "the other way than lfcam reads it");
  command.add_flag("--swap-axes", swap_axes,
                   "Take the names' rows as columns and their columns as rows: for names whose "
                   "two indices (or two numbers) come the other way round (before any --flip)");
  command.add_flag("--keep-axes", keep_axes,
                   "Keep the names' axes even where the views' own parallax says a row runs "
                   "against a column, or a rectified rig's occlusions say it stands half a turn "
                   "round (without this or a --flip or --swap flag lfcam does what the views "
                   "say, and says so)");
}

nlohmann::json ImportFlags::CheckAxes(ImportedGrid& grid) const {
  if (swap_axes) grid = WithAxesSwapped(grid);
  if (flip_rows || flip_cols) grid = WithAxesReversed(grid, flip_rows, flip_cols);
  ParallaxAxes axes = MeasureParallaxAxes(dir, grid);
  nlohmann::json j = {{"verdict", ToString(axes.verdict)},
                      {"points", axes.points},
                      {"correlation", axes.correlation},
                      {"largest_px_per_step", axes.largest_px_per_step},
                      {"swap_axes", swap_axes},
                      {"flip_rows", flip_rows},
                      {"flip_cols", flip_cols}};
  std::vector<std::string> said{Describe(axes)};
  // The flags say the user has chosen: what the views say is then reported, not acted on.
  if (swap_axes || flip_rows || flip_cols || keep_axes) {
    j["said"] = said.front();
    return j;
  }
  if (axes.verdict == AxesVerdict::kSwapped) {
    grid = WithAxesSwapped(grid);
    j["swap_axes"] = true;
    said.push_back(
        "the names' rows are taken as columns and their columns as rows (as --swap-axes would)");
    axes = MeasureParallaxAxes(dir, grid);
    j["largest_px_per_step"] = axes.largest_px_per_step;
    // (A single line of a rectified rig, taken the other way, has nothing to agree with.)
    if (axes.verdict == AxesVerdict::kSwapped ||
        (axes.verdict == AxesVerdict::kUndecided && !axes.single_line))
      throw Error(
          fmt::format("{}: {}; exchanged, they do not agree either ({}): describe the grid "
                      "in {} (docs/format.md), or give --keep-axes to import it as named",
                      dir, said.front(), Describe(axes), kViewsDescriptionName));
  }
  const bool rows =
      axes.verdict == AxesVerdict::kRowsReversed || axes.verdict == AxesVerdict::kBothReversed;
  const bool cols =
      axes.verdict == AxesVerdict::kColsReversed || axes.verdict == AxesVerdict::kBothReversed;
  if (rows || cols) {
    grid = WithAxesReversed(grid, rows, cols);
    j["flip_rows"] = rows;
    j["flip_cols"] = cols;
    if (said.size() > 1) said.push_back(Describe(axes));
    said.push_back(
        grid.rig == RigModel::kParallel
            ? fmt::format("the {} taken in reverse", rows && cols ? "rows and the columns are"
                                                     : rows       ? "rows are"
                                                                  : "columns are")
            : fmt::format(
                  "the rows are taken in reverse (as --flip-rows would), so that they agree with "
                  "the columns. Which of the two was named the other way the parallax of a "
                  "rectified rig cannot tell; its occlusions decide below (where they cannot, "
                  "and near and far come out exchanged, import with {}--flip-cols instead)",
                  said.size() > 2 ? "--swap-axes " : ""));
  }
  if (said.size() > 1) said.back() += " (--keep-axes: as named)";
  j["said"] = fmt::format("{}", fmt::join(said, "; "));
  return j;
}

nlohmann::json ImportFlags::CheckOcclusionOrder(ImportedLightField& imported, ImportedGrid& grid,
                                                const ImportOptions& options, bool quiet) const {
  const OcclusionOrder order = MeasureOcclusionOrder(imported.lightfield);
  nlohmann::json j = {{"verdict", ToString(order.verdict)},
                      {"as_named", order.as_named},
                      {"reversed", order.reversed},
                      {"seconds", order.seconds},
                      {"turned", false},
                      {"said", Describe(order)}};
  // The flags say the user has chosen: what the occlusions say is then reported, not acted on.
  if (order.verdict != OcclusionVerdict::kReversed || swap_axes || flip_rows || flip_cols ||
      keep_axes)
    return j;
  grid = WithAxesReversed(grid, true, true);
  imported = ImportRectified(dir, grid, options, quiet);
  j["turned"] = true;
  j["said"] = Describe(order) +
              "; so the rig is taken turned half a turn, its rows and its columns in reverse "
              "(--keep-axes: as named)";
  return j;
}

ImportedLightField ImportFlags::RunLenslet(bool quiet) const {
  if (naming != "auto" || !grid_shape.empty())
    throw UsageError(
        fmt::format("{}: a lenslet image's views are named and shaped by it (no "
                    "--naming or --grid)",
                    dir));
  const ImageHeader header = [&] {
    try {
      return ProbeImageFile(dir);
    } catch (const Error& e) {
      throw Error(fmt::format("not a folder, and not an image lfcam reads: {}", e.what()));
    }
  }();
  const cv::Mat image = ReadImageSrgb8(dir);
  int n = lenslet;
  nlohmann::json period = {{"views_per_side_given", lenslet > 0}};
  if (n == 0) {
    const LensletPeriod found = DetectLensletPeriod(image);
    if (found.views_per_side == 0)
      throw Error(fmt::format(
          "{}: {}x{} pixels with no block of N x N (N from 3 to 32 dividing both sides) whose "
          "positions differ in brightness as a lenslet image's do (the strongest {:.3f}, under "
          "{}): not a lenslet image? --lenslet N says how many views a side it holds",
          dir, image.cols, image.rows, found.strength, kLensletStrength));
    n = found.views_per_side;
    period["strength"] = found.strength;
  } else if (image.cols % n != 0 || image.rows % n != 0) {
    throw Error(fmt::format("{}: --lenslet {}: its {}x{} pixels are not blocks of {}x{}", dir, n,
                            image.cols, image.rows, n, n));
  }
  period["views_per_side"] = n;
  period["file"] = dir;
  // The views, as a plenoptic camera's NAME_RR_CC.png (row 01 at the top), in a folder of their
  // own that is removed whatever happens.
  static std::atomic<int> serial{0};
  struct Folder {
    std::filesystem::path path;
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  } views{std::filesystem::temp_directory_path() /
          fmt::format("lfcam_lenslet_{}_{}", ::getpid(), serial++)};
  std::filesystem::remove_all(views.path);
  std::filesystem::create_directories(views.path);
  WriteLensletViews(image, n, views.path);
  ImportFlags folder = *this;
  folder.dir = views.path.string();
  folder.naming = "unit-grid";
  ImportedLightField imported = folder.Run(quiet);
  const std::string said = fmt::format(
      "{} read as a lenslet image: {} x {} views of {}x{} (each {}x{} block of pixels one "
      "microlens's){}{}",
      dir, n, n, image.cols / n, image.rows / n, n, n,
      lenslet > 0 ? "" : ", the block's size found from its pixels (--lenslet N sets it)",
      header.bits_per_channel > 8 ? "; its 16 bits a channel stored as 8 (sRGB)" : "");
  SayFirst(imported, said);
  nlohmann::json& meta = imported.lightfield.metadata()["import"];
  meta["folder"] = dir;
  meta["lenslet"] = period;
  imported.summary["lenslet"] = period;
  // The views' names are the split's, not the user's: say which pixels each came from.
  for (auto& v : imported.summary["views"]) {
    int a = 0, b = 0;
    if (std::sscanf(v["file"].get<std::string>().c_str(), "view_%d_%d.png", &a, &b) == 2)
      v["file"] = fmt::format("{} (pixel {}, {} of each block)", dir, a - 1, b - 1);
  }
  return imported;
}

ImportedLightField ImportFlags::Run(bool quiet) const {
  {
    std::error_code ec;
    if (std::filesystem::is_regular_file(dir, ec)) return RunLenslet(quiet);
  }
  if (lenslet > 0)
    throw UsageError(fmt::format("--lenslet: {} is not one image (a lenslet image's file)", dir));
  if (const auto within = ViewsSubfolder(dir)) {
    ImportFlags folder = *this;
    folder.dir = within->string();
    ImportedLightField imported = folder.Run(quiet);
    SayFirst(imported, fmt::format("{} holds no views of its own: the views of {} imported", dir,
                                   folder.dir));
    return imported;
  }
  ImportOptions o;
  auto positive = [](const char* flag, double value) -> std::optional<double> {
    if (value == 0) return std::nullopt;
    if (!(value > 0) || !std::isfinite(value))
      throw UsageError(fmt::format("{} must be positive", flag));
    return value;
  };
  o.st_distance_mm = positive("--st-distance", st_distance);
  o.focal_px = positive("--focal-px", focal_px);
  o.focal_mm = positive("--focal-mm", focal_mm);
  o.sensor_width_mm = positive("--sensor-width-mm", sensor_width_mm);
  o.pitch_mm = positive("--pitch-mm", pitch_mm);
  o.fill_dark_views = !keep_dark_views;
  std::optional<GridNaming> grid_naming;
  if (naming != "auto")
    grid_naming = FlagValue("--naming", [&] { return GridNamingFromString(naming); });
  if (rig != "auto") o.rig = FlagValue("--rig", [&] { return RigModelFromString(rig); });
  if (o.focal_mm.has_value() != o.sensor_width_mm.has_value())
    throw UsageError("--focal-mm and --sensor-width-mm go together");
  BuildOptions b;
  if (!st_domain.empty()) b.st_domain = ParseStDomain("--st-domain", st_domain);
  std::optional<std::pair<int, int>> st_size;
  if (!st_res.empty()) st_size = ParseSize("--st-res", st_res, kMaxStSamplesPerSide);
  b.resampling = FlagValue("--resampling", [&] { return ResamplingFromString(resampling); });
  b.chroma = FlagValue("--chroma", [&] { return ChromaUpsamplingFromString(chroma); });
  b.allow_missing = allow_missing;

  std::optional<GridShape> shape;
  if (!grid_shape.empty()) {
    const auto [rows, cols] = ParseSize("--grid", grid_shape, kMaxViewsPerSide);
    shape = GridShape{rows, cols};
  }
  ImportedGrid grid = ScanGridFolder(dir, allow_missing, grid_naming, shape);
  if (o.rig) grid.rig = *o.rig;
  const nlohmann::json axes = CheckAxes(grid);
  if (grid.rig == RigModel::kRectified) {
    // Where no distance is known, infinity is put behind the zero-disparity plane by twice the
    // largest parallax the views show (a whole px, at least 1), so that the depth sweep's span
    // (half to twenty times that plane's distance) holds the scene either way round and little
    // more: a span many times the scene's lets a repeating texture match at a false depth
    // (docs/format.md, "What a data set does not say"). Where the parallax was not measured,
    // kAssumedInfinityDisparityPx.
    if (const double largest = axes.value("largest_px_per_step", 0.0); largest > 0) {
      o.infinity_disparity_px = SceneBracketPx(largest);
      o.scene_parallax_px = largest;
    }
    for (const CLI::Option* flag : {st_res_, st_domain_, resampling_, st_windows_})
      if (flag && flag->count() > 0)
        throw UsageError(fmt::format(
            "{}: a rectified rig's views are stored sample for sample, not resampled (--rig "
            "parallel resamples them)",
            flag->get_name()));
    ImportedLightField imported = ImportRectified(dir, grid, o, quiet);
    nlohmann::json order = CheckOcclusionOrder(imported, grid, o, quiet);
    imported.summary["axes"] = axes;
    if (order.value("turned", false)) {
      const bool rows = !axes.value("flip_rows", false), cols = !axes.value("flip_cols", false);
      imported.summary["axes"]["flip_rows"] = rows;
      imported.summary["axes"]["flip_cols"] = cols;
      if (cols && !rows)
        order["said"] = order["said"].get<std::string>() +
                        "; with the rows' reversal above, the columns are what is taken in "
                        "reverse (as --flip-cols would)";
    }
    imported.summary["occlusions"] = std::move(order);
    return imported;
  }
  if (o.pitch_mm && grid.positions_known)
    throw UsageError("--pitch-mm: the names give the cameras' positions");
  const ImportedSession session = MakeImportedSession(dir, grid, o);
  // By default the views' own sample spacing, each view in its own window.
  b.view_windows = ParseStWindows("--st-windows", st_windows);
  const StDomain& domain = b.st_domain.value_or(session.calibration.slab.st_domain);
  std::tie(b.n_s, b.n_t) =
      st_size.value_or(std::pair{int(std::lround(grid.width * domain.s_extent())),
                                 int(std::lround(grid.height * domain.t_extent()))});
  ProgressBar progress("importing views", std::int64_t(grid.rows) * grid.cols,
                       ProgressWanted(quiet));
  if (const auto advance = progress.callback()) b.view_done = [advance] { advance(1); };
  b.fill_dark_views = o.fill_dark_views;
  BuildReport report;
  LightField lf = BuildLightField(dir, session.manifest, session.calibration, b, &report);
  progress.finish();
  std::vector<std::string> dark;
  for (const auto& [row, col] : report.dark)
    dark.push_back(
        fmt::format("{} ({}, {})", grid.views[std::size_t(row * grid.cols + col)].file, row, col));
  return Imported(std::move(lf), grid, grid.rig, report.filled, report.seconds,
                  {{"axes", axes},
                   {"pitch_mm", grid.pitch_mm},
                   {"focal_px", session.focal_px},
                   {"st_distance_mm", session.st_distance_mm},
                   {"st_distance_estimated", session.st_distance_estimated},
                   {"st_distance_estimate_mm",
                    session.st_distance_unsnapped_mm.value_or(session.st_distance_mm)},
                   {"st_distance_snapped", session.st_distance_unsnapped_mm.has_value()},
                   {"notes", NamingNotes(grid)},
                   {"samples_between_neighbours", session.samples_between_neighbours},
                   {"dark", dark}});
}

std::unique_ptr<ImportRequest> ParseImportKeywords(const std::string& dir,
                                                   const std::vector<KeywordArgument>& arguments) {
  const KeywordTable& table = ImportKeywordTable();
  auto request = std::make_unique<ImportRequest>();
  request->parser = std::make_unique<CLI::App>("lfcam.import_views", "import");
  request->flags.AddTo(*request->parser);
  request->flags.dir = dir;
  ParseKeywords(*request->parser, table, arguments);
  return request;
}

}  // namespace lfcam::cli
