// `import lfcam`: the library from Python (docs/python.md). Light fields open without copying
// their samples; errors are Python exceptions carrying lfcam's messages: lfcam.Error (a
// RuntimeError) for what went wrong, lfcam.UsageError (also a ValueError) for what was asked
// wrongly.
#include <pybind11/stl.h>

#include "lfcam/core/error.h"
#include "lfcam/python/bindings.h"

namespace lfcam::python {

py::array ArrayOver(const py::dtype& dtype, std::vector<py::ssize_t> shape,
                    std::vector<py::ssize_t> strides, const void* data, py::handle base,
                    bool writable) {
  py::array array(dtype, std::move(shape), std::move(strides), data, base);
  if (!writable) array.attr("setflags")(py::arg("write") = false);
  return array;
}

py::array ArrayOfMat(const cv::Mat& image, bool flip_rows) {
  auto* held = new cv::Mat(image);
  py::capsule owner(held, [](void* p) { delete static_cast<cv::Mat*>(p); });
  const int depth = image.depth();
  const py::dtype dtype = depth == CV_8U    ? py::dtype::of<std::uint8_t>()
                          : depth == CV_16U ? py::dtype::of<std::uint16_t>()
                          : depth == CV_32S ? py::dtype::of<std::int32_t>()
                          : depth == CV_32F ? py::dtype::of<float>()
                                            : py::dtype::of<double>();
  const auto row = py::ssize_t(image.step[0]);
  const auto element = py::ssize_t(image.elemSize());
  const auto channel = py::ssize_t(image.elemSize1());
  const std::uint8_t* first = image.data + (flip_rows ? (image.rows - 1) * image.step[0] : 0);
  std::vector<py::ssize_t> shape = {image.rows, image.cols};
  std::vector<py::ssize_t> strides = {flip_rows ? -row : row, element};
  if (image.channels() > 1) {
    shape.push_back(image.channels());
    strides.push_back(channel);
  }
  return ArrayOver(dtype, shape, strides, first, owner, /*writable=*/true);
}

py::object ToPython(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

}  // namespace lfcam::python

PYBIND11_MODULE(lfcam, m) {
  namespace py = pybind11;
  m.doc() =
      "lfcam: 4D light fields from camera arrays: open, render through the paper's virtual "
      "camera, estimate depth, export, read capture sessions (docs/python.md)";
  m.attr("__version__") = LFCAM_VERSION;
  static py::exception<lfcam::Error> error(m, "Error", PyExc_RuntimeError);
  // Held for the interpreter's life (never released: a type outlives every module teardown).
  static PyObject* usage_error = PyErr_NewException(
      "lfcam.UsageError", py::make_tuple(error, py::handle(PyExc_ValueError)).ptr(), nullptr);
  m.attr("UsageError") = py::handle(usage_error);
  // The most derived first: translators run last registered first.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const lfcam::UsageError& e) {
      PyErr_SetString(usage_error, e.what());
    } catch (const lfcam::Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });
  lfcam::python::BindLightField(m);
  lfcam::python::BindRender(m);
  lfcam::python::BindDepth(m);
  lfcam::python::BindExport(m);
  lfcam::python::BindImport(m);
  lfcam::python::BindSession(m);
}
