// lfcam.import_views(dir, **keywords): a light field from a folder of views someone else made,
// as `lfcam import` makes it (cli/import_flags.h), every flag of import a keyword argument; and
// LightField.save(path) to keep it.
#include <pybind11/stl.h>

#include "lfcam/cli/import_flags.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/python/bindings.h"

namespace lfcam::python {

void BindImport(py::module_& m) {
  m.def(
      "import_views",
      [](const std::string& dir, const py::kwargs& kwargs) {
        const std::vector<cli::KeywordArgument> arguments = KeywordArguments(kwargs);
        std::shared_ptr<LightField> lf;
        nlohmann::json summary;
        {
          py::gil_scoped_release release;
          const auto request = cli::ParseImportKeywords(dir, arguments);
          cli::ImportedLightField imported = [&] {
            try {
              return request->flags.Run(/*quiet=*/true);
            } catch (const UsageError& e) {
              throw UsageError(cli::InKeywords(cli::ImportKeywordTable(), e.what()));
            }
          }();
          lf = std::make_shared<LightField>(std::move(imported.lightfield));
          summary = std::move(imported.summary);
          summary["ignored"] = imported.ignored;
        }
        return py::make_tuple(lf, ToPython(summary));
      },
      py::arg("dir"),
      R"(Imports a folder of views on a camera grid (the Stanford archive's, a Blender grid's,
the HCI benchmark's, plenoptic NAME_RR_CC views, or any described in lfcam-views.json), as
`lfcam import` does. Keywords are import's flags without the dashes: naming, rig, st_distance,
pitch_mm, st_res ((W, H)), st_domain ((s0, t0, s1, t1)), st_windows, focal_px, focal_mm,
sensor_width_mm, resampling, chroma, allow_missing, keep_dark_views, lenslet (dir then one
lenslet image), swap_axes, flip_rows, flip_cols, keep_axes.

Returns (LightField, summary): the light field in memory (LightField.save writes it) and what
`lfcam import --json` says of it: the rig, the geometry, what was assumed or filled.)");

  py::class_<LightField, std::shared_ptr<LightField>> light_field =
      py::reinterpret_borrow<py::class_<LightField, std::shared_ptr<LightField>>>(
          m.attr("LightField"));
  light_field.def(
      "save",
      [](const LightField& lf, const std::string& path, const std::string& compress) {
        LightFieldWriteOptions options;
        options.compression = cli::ParseCompression("compress", compress);
        py::gil_scoped_release release;
        WriteLightField(lf, path, options);
      },
      py::arg("path"), py::arg("compress") = "none",
      "Writes the light field to `path` (.lf), atomically; compress: none or zstd.");
}

}  // namespace lfcam::python
