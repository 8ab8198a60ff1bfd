#include "lfcam/share/quilt_export.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/staged_folder.h"
#include "lfcam/render/view_file.h"
#include "lfcam/share/mp4_writer.h"

namespace lfcam {

namespace fs = std::filesystem;

QuiltExportReport ExportQuilt(const QuiltExportJob& job, const FrameRenderer& renderer,
                              const fs::path& out_dir) {
  QuiltExportReport report;
  report.layout = LayoutQuilt(job.preset, /*even=*/job.video);
  const QuiltLayout& layout = report.layout;
  const std::vector<VirtualCameraParams> cameras =
      QuiltCameras(job.centre, layout, job.baseline_mm);
  Mp4Options mp4;
  mp4.fps = job.fps;
  if (job.video) RequireMp4Frame(layout.width(), layout.height(), mp4);
  StagedFolder folder(out_dir);
  const std::string name = job.stem + layout.suffix() + (job.video ? ".mp4" : ".png");
  report.file = folder.out() / name;

  fs::create_directories(folder.path() / "cameras");
  nlohmann::json views = nlohmann::json::array();
  for (std::size_t k = 0; k < cameras.size(); ++k) {
    const std::string file = fmt::format("cameras/view_{:02}.json", k);
    ViewSettings view;
    view.camera = cameras[k];
    view.integrator = job.render.integrator;
    view.interpolation = job.render.interpolation;
    WriteViewFile((folder.path() / file).string(), view);
    views.push_back(file);
  }
  nlohmann::json info = {
      {"format", "lfcam-quilt"},
      {"version", 1},
      {"file", name},
      {"display", job.preset.display},
      {"preset", job.preset.name},
      {"view_cone_deg", job.preset.view_cone_deg},
      {"columns", layout.cols},
      {"rows", layout.rows},
      {"aspect", layout.aspect},
      {"tile", {layout.tile_width, layout.tile_height}},
      {"view_render_size", {layout.render_width, layout.render_height}},
      {"order",
       "view 0 the leftmost camera in the bottom-left tile, then left to right, bottom "
       "to top"},
      {"baseline_mm", job.baseline_mm},
      {"zero_parallax_mm", job.centre.focus_distance_mm},
      {"frames", job.video ? job.frames : 1},
      {"views", views}};
  if (job.video) info["fps"] = job.fps;
  const std::string text = info.dump(2) + "\n";
  WriteFileAtomically(folder.path() / "quilt.json",
                      {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});

  const auto view_done = [&] {
    if (job.progress) job.progress(1);
  };
  if (!job.video) {
    WriteImage(folder.path() / name,
               RenderQuilt(job.light_field(0), layout, cameras, renderer, job.render, view_done));
    report.frames = 1;
  } else {
    Mp4Writer writer(folder.path() / name, layout.width(), layout.height(), mp4);
    for (int k = 0; k < job.frames; ++k)
      writer.Write(
          RenderQuilt(job.light_field(k), layout, cameras, renderer, job.render, view_done));
    writer.Finish();
    report.frames = writer.frames();
  }
  folder.Commit();
  return report;
}

}  // namespace lfcam
