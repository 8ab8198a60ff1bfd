// lfcam.depth(lf, row, col): a view's depth map by the plane sweep `lfcam depth` runs.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <optional>

#include "lfcam/core/error.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/python/bindings.h"

namespace lfcam::python {

void BindDepth(py::module_& m) {
  m.def(
      "depth",
      [](const std::shared_ptr<LightField>& lf, std::optional<int> row, std::optional<int> col,
         std::optional<double> near_mm, std::optional<double> far_mm) {
        const int r = row.value_or(lf->dims().rows / 2), c = col.value_or(lf->dims().cols / 2);
        if (r < 0 || r >= lf->dims().rows || c < 0 || c >= lf->dims().cols)
          throw UsageError(fmt::format("view ({}, {}): not in the light field's {}x{} views", r, c,
                                       lf->dims().rows, lf->dims().cols));
        if (near_mm.has_value() != far_mm.has_value())
          throw UsageError("near and far go together (the depths swept, mm)");
        PlaneSweepOptions options;
        if (near_mm) {
          options.range = DepthRange{*near_mm, *far_mm};
          if (!options.range->valid())
            throw UsageError(
                fmt::format("near {} and far {}: need 0 < near < far (mm)", *near_mm, *far_mm));
        }
        DepthMap map;
        {
          py::gil_scoped_release release;
          map = EstimateDepth(*lf, r, c, options);
        }
        py::dict result;
        result["depth"] = ArrayOfMat(map.depth, /*flip_rows=*/true);
        result["confidence"] = map.confidence.empty()
                                   ? py::object(py::none())
                                   : py::object(ArrayOfMat(map.confidence, /*flip_rows=*/true));
        result["near_mm"] = map.range.near_mm;
        result["far_mm"] = map.range.far_mm;
        result["row"] = r;
        result["col"] = c;
        return result;
      },
      py::arg("lightfield"), py::arg("row") = py::none(), py::arg("col") = py::none(),
      py::kw_only(), py::arg("near") = py::none(), py::arg("far") = py::none(),
      R"(The depth map of view (row, col) (default: the centre view), by `lfcam depth`'s plane
sweep: a dict with "depth" (n_t x n_s float32, mm from the camera plane, NaN where unknown,
top row first, like LightField.view), "confidence" (0 .. 1), and the range swept ("near_mm",
"far_mm": estimated unless near and far are given).)");
}

}  // namespace lfcam::python
