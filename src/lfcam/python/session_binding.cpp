// lfcam.read_session(DIR): a capture session's manifest (`lfcam capture shoot`/`record`,
// `lfcam simulate capture`) as Python objects.
#include <pybind11/stl.h>

#include "lfcam/python/bindings.h"
#include "lfcam/session/session.h"

namespace lfcam::python {

void BindSession(py::module_& m) {
  m.def(
      "read_session",
      [](const std::string& dir) {
        CaptureManifest manifest;
        {
          py::gil_scoped_release release;
          manifest = ReadManifest(dir);
        }
        return ToPython(ManifestToJson(manifest));
      },
      py::arg("session"),
      R"(A capture session's manifest (DIR/manifest.json, checked as `lfcam calibrate` checks
it) as a dict: the grid, the sensor, the boards and every shot with each camera's image and
what the capture recorded of it (docs/capture-layout.md). Raises lfcam.Error naming what is
wrong.)");
}

}  // namespace lfcam::python
