// `lfcam import DIR --out FILE`: a light field from a folder of views someone else made (the
// Stanford archive's, a Blender camera grid's, the HCI benchmark's, plenoptic views, or any
// described in lfcam-views.json): a rectified rig's views stored sample for sample, a parallel
// rig's through the same resampler as `build` (docs/format.md, "Importing").
#include <fmt/core.h>

#include <memory>

#include "lfcam/calib/lightfield_build.h"
#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/io/rectified_import.h"

namespace lfcam::cli {

namespace {

// Which file became which view (lfcam's grid: row 0 at the bottom), for --json.
nlohmann::json ViewFiles(const ImportedGrid& grid) {
  nlohmann::json views = nlohmann::json::array();
  for (const GridView& v : grid.views)
    views.push_back({{"row", v.row}, {"col", v.col}, {"file", v.file}});
  return views;
}

// A rectified rig: the views as they are, with the geometry said (and what was assumed).
void ImportRectified(const std::string& dir, const ImportedGrid& grid, const ImportOptions& o,
                     const std::string& out, const LightFieldWriteOptions& w, bool quiet,
                     bool json) {
  const RectifiedGeometry geometry = ResolveRectifiedGeometry(grid, o);
  ProgressBar progress("importing views", std::int64_t(grid.rows) * grid.cols,
                       ProgressWanted(quiet || json));
  const auto advance = progress.callback();
  RectifiedImportReport report;
  const LightField lf = ImportRectifiedViews(
      dir, grid, geometry,
      [&] {
        if (advance) advance(1);
      },
      &report);
  progress.finish();
  WriteLightField(lf, out, w);
  const nlohmann::json summary = {{"out", out},
                                  {"naming", ToString(grid.naming)},
                                  {"rig", ToString(RigModel::kRectified)},
                                  {"rows", grid.rows},
                                  {"cols", grid.cols},
                                  {"view_width", grid.width},
                                  {"view_height", grid.height},
                                  {"pitch_mm", geometry.pitch_mm},
                                  {"focal_px", geometry.focal_px},
                                  {"st_distance_mm", geometry.zero_disparity_mm},
                                  {"zero_disparity_distance_mm", geometry.zero_disparity_mm},
                                  {"st_distance_estimated", false},
                                  {"assumed", geometry.assumed},
                                  {"n_s", lf.dims().n_s},
                                  {"n_t", lf.dims().n_t},
                                  {"filled", report.filled},
                                  {"views", ViewFiles(grid)},
                                  {"seconds", report.seconds}};
  if (json) {
    fmt::print("{}\n", JsonToText(summary, 2));
    return;
  }
  fmt::print(
      "imported {}x{} views of {}x{} ({} naming, rectified rig), pitch {:.4g}, focal length "
      "{:.1f} px\n",
      grid.rows, grid.cols, grid.width, grid.height, ToString(grid.naming), geometry.pitch_mm,
      geometry.focal_px);
  fmt::print(
      "  st-plane on the zero-disparity plane, {:.4g} from the cameras; each view's "
      "{}x{} pixels stored as they are, in {:.2f} s\n",
      geometry.zero_disparity_mm, lf.dims().n_s, lf.dims().n_t, report.seconds);
  for (const std::string& assumed : geometry.assumed) fmt::print("  assumed: {}\n", assumed);
  for (const auto& filled : report.filled)
    fmt::print(stderr, "lfcam: warning: filled {}\n", filled);
  fmt::print("wrote {}\n", out);
}

}  // namespace

void AddImportCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "import",
      "Import a folder of views on a camera grid (Stanford, Blender grid, HCI benchmark, "
      "plenoptic NAME_RR_CC views, described)");
  struct Flags {
    std::string dir, out, st_res, st_domain, compression = "none", resampling = "linear",
                                             chroma = "guided", naming = "auto", rig = "auto",
                                             st_windows = "views";
    double st_distance = 0, focal_px = 0, focal_mm = 0, sensor_width_mm = 0, pitch_mm = 0;
    bool allow_missing = false, json = false, quiet = false;
  };
  auto f = std::make_shared<Flags>();
  command->add_option("dir", f->dir, "The folder of views")->required();
  command->add_option("--out", f->out, "Light field file to write (.lf)")->required();
  command
      ->add_option("--naming", f->naming,
                   "How the views are named: auto, stanford (NAME_RR_CC_Y_X_), blender-grid "
                   "(NAME_RR_CC_Y_X_F_W), hci (input_CamNNN.png + parameters.cfg) or unit-grid "
                   "(NAME_RR_CC: indices only, row 1 at the top); auto refuses names that parse "
                   "several ways")
      ->capture_default_str();
  command
      ->add_option("--rig", f->rig,
                   "auto, parallel (centred sensors: zero disparity at infinity) or rectified "
                   "(shifted sensors: zero disparity on one plane, the st-plane; views stored "
                   "sample for sample); auto: Blender grids parallel, the others rectified")
      ->capture_default_str();
  command->add_option("--st-distance", f->st_distance,
                      "Distance of the st-plane from the cameras, mm. Parallel rig: default the "
                      "description's, else the depth most of the scene lies at, estimated. "
                      "Rectified rig: the zero-disparity plane's (default the description's or "
                      "parameters.cfg's, else assumed and said)");
  command->add_option("--pitch-mm", f->pitch_mm,
                      "The cameras' spacing, for views named by indices alone (default 1, said)");
  auto* st_res = command->add_option(
      "--st-res", f->st_res,
      "Parallel rig: st samples per view, N_SxN_T (default: the views' sample spacing "
      "over the st domain)");
  auto* st_domain = command->add_option(
      "--st-domain", f->st_domain,
      "Parallel rig: sampled st domain S0,T0,S1,T1 (view-window units, [0, 1]^2 being what the "
      "central camera sees on the st-plane, the default)");
  auto* st_windows =
      command
          ->add_option("--st-windows", f->st_windows,
                       "Parallel rig: views (each view in its own window, the st domain's grid "
                       "moved to where its camera looks: its own pixels) or shared (every view "
                       "samples the st domain)")
          ->capture_default_str();
  command->add_option("--focal-px", f->focal_px, "The views' focal length in pixels");
  command->add_option("--focal-mm", f->focal_mm,
                      "The lens's focal length, mm (with --sensor-width-mm)");
  command->add_option("--sensor-width-mm", f->sensor_width_mm, "The sensor's width, mm");
  command->add_option("--compress", f->compression, "none or zstd")->capture_default_str();
  auto* resampling = command
                         ->add_option("--resampling", f->resampling,
                                      "Parallel rig: linear, cubic or lanczos4 (as for build)")
                         ->capture_default_str();
  command
      ->add_option("--chroma", f->chroma, "guided or interpolated, for JPEG views (as for build)")
      ->capture_default_str();
  command->add_flag("--allow-missing", f->allow_missing,
                    "Fill views missing from the grid from their nearest neighbours (recorded)");
  command->add_flag("--json", f->json, "Print a summary as JSON on stdout");
  command->add_flag("--quiet", f->quiet, "No progress bar");
  command->callback([f, st_res, st_domain, resampling, st_windows] {
    ImportOptions o;
    auto positive = [](const char* flag, double value) -> std::optional<double> {
      if (value == 0) return std::nullopt;
      if (!(value > 0) || !std::isfinite(value))
        throw UsageError(fmt::format("{} must be positive", flag));
      return value;
    };
    o.st_distance_mm = positive("--st-distance", f->st_distance);
    o.focal_px = positive("--focal-px", f->focal_px);
    o.focal_mm = positive("--focal-mm", f->focal_mm);
    o.sensor_width_mm = positive("--sensor-width-mm", f->sensor_width_mm);
    o.pitch_mm = positive("--pitch-mm", f->pitch_mm);
    std::optional<GridNaming> naming;
    if (f->naming != "auto")
      naming = FlagValue("--naming", [&] { return GridNamingFromString(f->naming); });
    if (f->rig != "auto") o.rig = FlagValue("--rig", [&] { return RigModelFromString(f->rig); });
    if (o.focal_mm.has_value() != o.sensor_width_mm.has_value())
      throw UsageError("--focal-mm and --sensor-width-mm go together");
    BuildOptions b;
    if (!f->st_domain.empty()) b.st_domain = ParseStDomain("--st-domain", f->st_domain);
    std::optional<std::pair<int, int>> st_size;
    if (!f->st_res.empty()) st_size = ParseSize("--st-res", f->st_res, kMaxStSamplesPerSide);
    b.resampling = FlagValue("--resampling", [&] { return ResamplingFromString(f->resampling); });
    b.chroma = FlagValue("--chroma", [&] { return ChromaUpsamplingFromString(f->chroma); });
    b.allow_missing = f->allow_missing;
    LightFieldWriteOptions w;
    w.compression = ParseCompression("--compress", f->compression);
    RequireWritableOutput(f->out, "--out");

    ImportedGrid grid = ScanGridFolder(f->dir, f->allow_missing, naming);
    if (o.rig) grid.rig = *o.rig;
    for (const std::string& ignored : grid.ignored)
      if (!f->json) fmt::print(stderr, "lfcam: note: {} is not a view: left out\n", ignored);
    if (grid.rig == RigModel::kRectified) {
      for (const CLI::Option* flag : {st_res, st_domain, resampling, st_windows})
        if (flag->count() > 0)
          throw UsageError(fmt::format(
              "{}: a rectified rig's views are stored sample for sample, not resampled (--rig "
              "parallel resamples them)",
              flag->get_name()));
      ImportRectified(f->dir, grid, o, f->out, w, f->quiet, f->json);
      return;
    }
    if (o.pitch_mm && grid.positions_known)
      throw UsageError("--pitch-mm: the names give the cameras' positions");
    const ImportedSession session = MakeImportedSession(f->dir, grid, o);
    // By default the views' own sample spacing, each view in its own window.
    b.view_windows = ParseStWindows("--st-windows", f->st_windows);
    const StDomain& domain = b.st_domain.value_or(session.calibration.slab.st_domain);
    std::tie(b.n_s, b.n_t) =
        st_size.value_or(std::pair{int(std::lround(grid.width * domain.s_extent())),
                                   int(std::lround(grid.height * domain.t_extent()))});
    ProgressBar progress("importing views", std::int64_t(grid.rows) * grid.cols,
                         ProgressWanted(f->quiet || f->json));
    if (const auto advance = progress.callback()) b.view_done = [advance] { advance(1); };
    BuildReport report;
    const LightField lf =
        BuildLightField(f->dir, session.manifest, session.calibration, b, &report);
    progress.finish();
    WriteLightField(lf, f->out, w);
    const nlohmann::json summary = {
        {"out", f->out},
        {"naming", ToString(grid.naming)},
        {"rig", ToString(grid.rig)},
        {"rows", grid.rows},
        {"cols", grid.cols},
        {"view_width", grid.width},
        {"view_height", grid.height},
        {"pitch_mm", grid.pitch_mm},
        {"focal_px", session.focal_px},
        {"st_distance_mm", session.st_distance_mm},
        {"st_distance_estimated", session.st_distance_estimated},
        {"st_distance_estimate_mm",
         session.st_distance_unsnapped_mm.value_or(session.st_distance_mm)},
        {"n_s", lf.dims().n_s},
        {"n_t", lf.dims().n_t},
        {"filled", report.filled},
        {"views", ViewFiles(grid)},
        {"seconds", report.seconds}};
    if (f->json) {
      fmt::print("{}\n", JsonToText(summary, 2));
      return;
    }
    fmt::print(
        "imported {}x{} views of {}x{} ({} naming), pitch {:.3f} mm, focal length {:.1f} px\n",
        grid.rows, grid.cols, grid.width, grid.height, ToString(grid.naming), grid.pitch_mm,
        session.focal_px);
    fmt::print(
        "  st-plane {:.0f} mm from the cameras{}; {}x{} st samples in {:.2f} s\n",
        session.st_distance_mm,
        !session.st_distance_estimated ? std::string()
        : session.st_distance_unsnapped_mm
            ? fmt::format(" (estimated: most of the scene is at {:.0f} mm; moved so that "
                          "neighbouring views lie {} samples apart there and every "
                          "view's pixels stay samples)",
                          *session.st_distance_unsnapped_mm, session.samples_between_neighbours)
            : std::string(" (estimated: where most of the scene is)"),
        lf.dims().n_s, lf.dims().n_t, report.seconds);
    for (const auto& filled : report.filled)
      fmt::print(stderr, "lfcam: warning: filled {}\n", filled);
    fmt::print("wrote {}\n", f->out);
  });
}

}  // namespace lfcam::cli
