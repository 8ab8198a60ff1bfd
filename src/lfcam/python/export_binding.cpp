// lfcam.export(lf, out, format): the views as PNGs with their cameras, NeRF's transforms.json or
// a COLMAP model, as `lfcam export` writes them.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "lfcam/core/error.h"
#include "lfcam/io/lightfield_export.h"
#include "lfcam/python/bindings.h"

namespace lfcam::python {

void BindExport(py::module_& m) {
  m.def(
      "export",
      [](const std::shared_ptr<LightField>& lf, const std::string& out, const std::string& format) {
        if (format != "png-views" && format != "nerf" && format != "colmap")
          throw UsageError(fmt::format("format '{}' is not png-views, nerf or colmap", format));
        const ExportFormat f = ExportFormatFromString(format);
        ExportReport report;
        {
          py::gil_scoped_release release;
          report = ExportLightField(*lf, f, out);
        }
        py::dict d;
        d["views"] = report.views;
        d["points"] = report.points;
        d["main_file"] = report.main_file.string();
        return d;
      },
      py::arg("lightfield"), py::arg("out"), py::arg("format") = "png-views",
      R"(Writes the light field's views for other tools into the folder `out` (created; it
must be empty if it exists): format "png-views" (each view a PNG and cameras.json), "nerf"
(transforms.json) or "colmap" (a text model). Everything appears at once or not at all.
Returns what was written.)");
}

}  // namespace lfcam::python
