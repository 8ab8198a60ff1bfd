// lfcam.open and lfcam.LightField: a light field file (.lf) or a frame of a light field video
// (.lfv), its samples as NumPy arrays over the file's own mapping (no copy), its geometry.
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>

#include "lfcam/core/lightfield.h"
#include "lfcam/core/lightfield_video_file.h"
#include "lfcam/io/lightfield_export.h"
#include "lfcam/python/bindings.h"

namespace lfcam::python {
namespace {

using LightFieldPtr = std::shared_ptr<LightField>;

py::dtype SampleDtype(SampleType type) {
  return type == SampleType::kSrgb8 ? py::dtype::of<std::uint8_t>() : py::dtype("float16");
}

// Every sample: (rows, cols, n_t, n_s, 3). `upright`: each view's rows top first (st rows are
// stored bottom-up), by walking them backwards.
py::array Samples(const LightFieldPtr& lf, bool upright) {
  const LightFieldDims& d = lf->dims();
  const auto channel = py::ssize_t(BytesPerChannel(lf->sample_type()));
  const py::ssize_t sample = 3 * channel, row = d.n_s * sample;
  const auto view = py::ssize_t(lf->view_bytes());
  const std::uint8_t* first = lf->data() + (upright ? (d.n_t - 1) * row : 0);
  return ArrayOver(SampleDtype(lf->sample_type()), {d.rows, d.cols, d.n_t, d.n_s, 3},
                   {d.cols * view, view, upright ? -row : row, sample, channel}, first,
                   py::cast(lf));
}

void CheckView(const LightField& lf, int row, int col) {
  if (row < 0 || row >= lf.dims().rows || col < 0 || col >= lf.dims().cols)
    throw UsageError(
        fmt::format("view ({}, {}): the light field's views are rows 0 .. {} and "
                    "columns 0 .. {}",
                    row, col, lf.dims().rows - 1, lf.dims().cols - 1));
}

py::dict PlaneDict(const ArrayPlane& a) {
  py::dict d;
  d["corner"] = a.p_ca;
  d["u_axis"] = a.u_ca;
  d["v_axis"] = a.v_ca;
  d["normal"] = a.n_ca;
  d["rows"] = a.rows;
  d["cols"] = a.cols;
  d["pitch_mm"] = a.pitch_mm;
  return d;
}

py::dict SlabDict(const Slab& slab) {
  py::dict st;
  st["origin"] = slab.st.origin;
  st["s_axis"] = slab.st.x_axis;
  st["t_axis"] = slab.st.y_axis;
  st["width_mm"] = slab.st.width_mm;
  st["height_mm"] = slab.st.height_mm;
  py::dict d;
  d["uv"] = PlaneDict(slab.uv);
  d["st"] = st;
  d["st_domain"] =
      py::make_tuple(slab.st_domain.s0, slab.st_domain.t0, slab.st_domain.s1, slab.st_domain.t1);
  d["separation_mm"] = slab.separation_mm();
  return d;
}

Eigen::Matrix4d Homogeneous(const Rigid3& r) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = r.rotation;
  m.topRightCorner<3, 1>() = r.translation;
  return m;
}

}  // namespace

void BindLightField(py::module_& m) {
  py::class_<LightField, LightFieldPtr>(
      m, "LightField",
      "A 4D light field L(u, v, s, t): a grid of views (rows x cols, row 0 at the bottom as "
      "`lfcam info` lists them), each n_t x n_s samples of the st-plane. Its arrays are views of "
      "the file's own mapping: read-only, no copy.")
      .def_property_readonly("rows", [](const LightField& lf) { return lf.dims().rows; })
      .def_property_readonly("cols", [](const LightField& lf) { return lf.dims().cols; })
      .def_property_readonly("n_s", [](const LightField& lf) { return lf.dims().n_s; })
      .def_property_readonly("n_t", [](const LightField& lf) { return lf.dims().n_t; })
      .def_property_readonly("shape",
                             [](const LightField& lf) {
                               const auto& d = lf.dims();
                               return py::make_tuple(d.rows, d.cols, d.n_t, d.n_s, 3);
                             })
      .def_property_readonly("sample_type",
                             [](const LightField& lf) { return ToString(lf.sample_type()); })
      .def_property_readonly(
          "views", [](const LightFieldPtr& lf) { return Samples(lf, /*upright=*/true); },
          "Every view as an image: (rows, cols, n_t, n_s, 3), each view's top row first; uint8 "
          "sRGB (or float16 linear light for a linear-f16 file). No copy.")
      .def_property_readonly(
          "samples", [](const LightFieldPtr& lf) { return Samples(lf, /*upright=*/false); },
          "The samples as stored: (rows, cols, n_t, n_s, 3), st row l = 0 at the bottom of each "
          "view (docs/format.md). No copy.")
      .def(
          "view",
          [](const LightFieldPtr& lf, int row, int col) {
            CheckView(*lf, row, col);
            return Samples(lf, true)[py::make_tuple(row, col)].cast<py::array>();
          },
          py::arg("row"), py::arg("col"),
          "View (row, col) as an image, n_t x n_s x 3, top row first. No copy.")
      .def(
          "camera_center",
          [](const LightField& lf, int row, int col) -> Vec3 {
            CheckView(lf, row, col);
            return lf.camera_center(row, col);
          },
          py::arg("row"), py::arg("col"),
          "Where camera (row, col) was, world mm (measured where the file knows it).")
      .def(
          "camera",
          [](const LightField& lf, int row, int col) {
            CheckView(lf, row, col);
            const ViewCamera c = ViewAsCamera(lf, row, col);
            py::dict d;
            d["width"] = c.width;
            d["height"] = c.height;
            d["fx"] = c.fx;
            d["fy"] = c.fy;
            d["cx"] = c.cx;
            d["cy"] = c.cy;
            d["world_from_camera"] = Homogeneous(c.world_from_camera);
            return d;
          },
          py::arg("row"), py::arg("col"),
          "View (row, col) as a pinhole camera, OpenCV's conventions (x right, y down, z "
          "forward; pixel (0, 0) the centre of the top-left sample), as `lfcam export` writes it.")
      .def_property_readonly(
          "slab", [](const LightField& lf) { return SlabDict(lf.slab()); },
          "The two planes: the camera (uv) plane and the st-plane, world mm.")
      .def_property_readonly("metadata",
                             [](const LightField& lf) { return ToPython(lf.metadata()); })
      .def("__repr__", [](const LightField& lf) {
        const auto& d = lf.dims();
        return fmt::format("<lfcam.LightField {}x{} views of {}x{} samples, {}>", d.rows, d.cols,
                           d.n_s, d.n_t, ToString(lf.sample_type()));
      });

  m.def(
      "open",
      [](const std::string& path, std::size_t frame) {
        std::shared_ptr<LightField> lf;
        {
          py::gil_scoped_release release;
          lf = std::make_shared<LightField>(ReadLightFieldFrame(path, frame));
        }
        return lf;
      },
      py::arg("path"), py::arg("frame") = 0,
      "Opens a light field (.lf) or frame `frame` of a light field video (.lfv). The samples "
      "stay in the file's mapping. Raises lfcam.Error naming the file when it cannot be read.");
}

}  // namespace lfcam::python
