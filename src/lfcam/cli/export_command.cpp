// `lfcam export FILE --format png-views|nerf|colmap --out DIR`: a light field's views and
// cameras for other tools (docs/format.md, "Exporting").
#include <fmt/core.h>

#include <memory>

#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/io/lightfield_export.h"

namespace lfcam::cli {

void AddExportCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "export", "Export the views and their cameras: PNGs, NeRF transforms.json or COLMAP");
  struct Flags {
    std::string input, format, out;
  };
  auto f = std::make_shared<Flags>();
  command->add_option("lightfield", f->input, "Light field file (.lf)")->required();
  command->add_option("--format", f->format, "png-views, nerf or colmap")->required();
  command->add_option("--out", f->out, "The folder to write (new or empty)")->required();
  command->callback([f] {
    const ExportFormat format = ExportFormatFromString(f->format);
    RequireNewOrEmptyFolder("--out", f->out);
    const LightField lf = ReadLightField(f->input);
    const ExportReport report = ExportLightField(lf, format, f->out);
    fmt::print("wrote {} views and their cameras to {} ({})\n", report.views, f->out,
               report.main_file.string());
  });
}

}  // namespace lfcam::cli
