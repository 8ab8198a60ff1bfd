// `lfcam import DIR --out FILE`: a light field from a folder of views someone else made
// (cli/import_flags.h does the work; this writes it and says what it did).
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <memory>

#include "lfcam/cli/commands.h"
#include "lfcam/cli/import_flags.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/view_filling.h"

namespace lfcam::cli {
namespace {

void PrintImport(const nlohmann::json& s) {
  const bool rectified = s["rig"] == "rectified";
  if (rectified) {
    // "mm", or "units" of the cameras' spacing where nothing metric is known.
    const std::string unit = s.value("length_unit", "mm");
    fmt::print(
        "imported {}x{} views of {}x{} ({} naming, rectified rig), pitch {:.4g} {}, focal length "
        "{:.1f} px\n",
        s["rows"].get<int>(), s["cols"].get<int>(), s["view_width"].get<int>(),
        s["view_height"].get<int>(), s["naming"].get<std::string>(), s["pitch_mm"].get<double>(),
        unit, s["focal_px"].get<double>());
    fmt::print(
        "  st-plane on the zero-disparity plane, {:.4g} {} from the cameras; each view's "
        "{}x{} pixels stored as they are, in {:.2f} s\n",
        s["zero_disparity_distance_mm"].get<double>(), unit, s["n_s"].get<int>(),
        s["n_t"].get<int>(), s["seconds"].get<double>());
    for (const auto& assumed : s["assumed"])
      fmt::print("  assumed: {}\n", assumed.get<std::string>());
  } else {
    fmt::print(
        "imported {}x{} views of {}x{} ({} naming), pitch {:.3f} mm, focal length {:.1f} px\n",
        s["rows"].get<int>(), s["cols"].get<int>(), s["view_width"].get<int>(),
        s["view_height"].get<int>(), s["naming"].get<std::string>(), s["pitch_mm"].get<double>(),
        s["focal_px"].get<double>());
    std::string estimated;
    if (s["st_distance_estimated"].get<bool>())
      estimated = s["st_distance_snapped"].get<bool>()
                      ? fmt::format(
                            " (estimated: most of the scene is at {:.0f} mm; moved so that "
                            "neighbouring views lie {} samples apart there and every "
                            "view's pixels stay samples)",
                            s["st_distance_estimate_mm"].get<double>(),
                            s["samples_between_neighbours"].get<int>())
                      : std::string(" (estimated: where most of the scene is)");
    fmt::print("  st-plane {:.0f} mm from the cameras{}; {}x{} st samples in {:.2f} s\n",
               s["st_distance_mm"].get<double>(), estimated, s["n_s"].get<int>(),
               s["n_t"].get<int>(), s["seconds"].get<double>());
  }
  if (s.contains("notes"))
    for (const auto& note : s["notes"]) fmt::print("  note: {}\n", note.get<std::string>());
  if (s.contains("axes") && s["axes"]["verdict"] != "agree")
    fmt::print("  note: {}\n", s["axes"]["said"].get<std::string>());
  if (s.contains("occlusions"))
    fmt::print("  {}{} ({:.1f} s)\n", s["occlusions"]["verdict"] == "as-named" ? "" : "note: ",
               s["occlusions"]["said"].get<std::string>(),
               s["occlusions"]["seconds"].get<double>());
  if (s.contains("dark") && !s["dark"].empty())
    fmt::print("  note: {}\n", DarkViewsNote(s["dark"].get<std::vector<std::string>>()));
  for (const auto& filled : s["filled"])
    fmt::print(stderr, "lfcam: warning: filled {}\n", filled.get<std::string>());
}

}  // namespace

void AddImportCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "import",
      "Import a folder of views on a camera grid (Stanford, Blender grid, HCI benchmark, "
      "plenoptic NAME_RR_CC views or one lenslet image, described)");
  struct Flags {
    ImportFlags import;
    std::string out, compression = "none";
    bool json = false, quiet = false;
  };
  auto f = std::make_shared<Flags>();
  command->add_option("dir", f->import.dir, "The folder of views, or one lenslet image (ESLF)")
      ->required();
  command->add_option("--out", f->out, "Light field file to write (.lf)")->required();
  f->import.AddTo(*command);
  command->add_option("--compress", f->compression, "none or zstd")->capture_default_str();
  command->add_flag("--json", f->json, "Print a summary as JSON on stdout");
  command->add_flag("--quiet", f->quiet, "No progress bar");
  command->callback([f] {
    LightFieldWriteOptions w;
    w.compression = ParseCompression("--compress", f->compression);
    RequireWritableOutput(f->out, "--out");
    ImportedLightField imported = f->import.Run(f->quiet || f->json);
    if (!f->json)
      for (const std::string& ignored : imported.ignored)
        fmt::print(stderr, "lfcam: note: {} is not a view: left out\n", ignored);
    WriteLightField(imported.lightfield, f->out, w);
    imported.summary["out"] = f->out;
    if (f->json) {
      fmt::print("{}\n", JsonToText(imported.summary, 2));
      return;
    }
    PrintImport(imported.summary);
    fmt::print("wrote {}\n", f->out);
  });
}

}  // namespace lfcam::cli
