// `lfcam export FILE --format png-views|nerf|colmap --out DIR [--depth DIR]`: a light field's
// views and cameras for other tools (docs/format.md, "Exporting"); 3D points from depth maps
// (`lfcam depth --all`) for COLMAP and nerfstudio.
#include <fmt/core.h>

#include <memory>
#include <optional>

#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/lightfield_video_file.h"
#include "lfcam/io/lightfield_export.h"

namespace lfcam::cli {

void AddExportCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "export", "Export the views and their cameras: PNGs, NeRF transforms.json or COLMAP");
  struct Flags {
    int frame = 0;
    std::string input, format, out, depth;
  };
  auto f = std::make_shared<Flags>();
  command->add_option("lightfield", f->input, "Light field file (.lf) or video (.lfv)")->required();
  command->add_option("--frame", f->frame, "A video's light field frame (from 0)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1 << 30));
  command->add_option("--format", f->format, "png-views, nerf or colmap")->required();
  command->add_option("--out", f->out, "The folder to write (new or empty)")->required();
  command->add_option("--depth", f->depth,
                      "Depth maps of the light field (`lfcam depth --all`): 3D points from them, "
                      "with their tracks in COLMAP's points3D.txt (--format colmap), or in "
                      "sparse_pc.ply for nerfstudio's Gaussian splatting (--format nerf)");
  command->callback([f] {
    const ExportFormat format = ExportFormatFromString(f->format);
    if (!f->depth.empty() && format == ExportFormat::kPngViews)
      throw UsageError("--depth goes with --format colmap (points3D.txt) or nerf (sparse_pc.ply)");
    RequireNewOrEmptyFolder("--out", f->out);
    const LightField lf = ReadLightFieldFrame(f->input, std::size_t(f->frame));
    std::optional<DepthSet> depth;
    if (!f->depth.empty()) depth = ReadDepthSet(f->depth, lf);
    const ExportReport report = ExportLightField(lf, format, f->out, depth ? &*depth : nullptr);
    fmt::print("wrote {} views and their cameras to {} ({})\n", report.views, f->out,
               report.main_file.string());
    if (depth && format == ExportFormat::kColmap)
      fmt::print("  {} points from the depth maps of {} views, seen {} times in all\n",
                 report.points, depth->count(), report.observations);
    else if (depth)
      fmt::print("  {} points from the depth maps of {} views in sparse_pc.ply\n", report.points,
                 depth->count());
  });
}

}  // namespace lfcam::cli
