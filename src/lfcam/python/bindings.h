#pragma once
// The Python module `lfcam` (module.cpp), one file per part of the library it opens: light
// fields and their views (lightfield_binding.cpp), rendering (render_binding.cpp), depth
// (depth_binding.cpp), export (export_binding.cpp) and capture sessions (session_binding.cpp).
// docs/python.md is its guide.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "lfcam/cli/keyword_arguments.h"

namespace lfcam::python {

namespace py = pybind11;

void BindLightField(py::module_& m);
void BindRender(py::module_& m);
void BindDepth(py::module_& m);
void BindExport(py::module_& m);
void BindImport(py::module_& m);
void BindSession(py::module_& m);

// An array over memory another object keeps alive (`base`): no copy. Read-only unless
// `writable`. Strides in bytes; a negative one walks backwards from `data`.
py::array ArrayOver(const py::dtype& dtype, std::vector<py::ssize_t> shape,
                    std::vector<py::ssize_t> strides, const void* data, py::handle base,
                    bool writable = false);

// An image (rows top first) as an H x W (x C) array that owns the cv::Mat's buffer: no copy.
// `flip_rows`: the matrix's row 0 is the image's bottom row (st rows, depth maps), walked
// backwards so that the array's row 0 is the top.
py::array ArrayOfMat(const cv::Mat& image, bool flip_rows = false);

// Python keyword arguments as keyword values; a value no flag takes is a TypeError naming the
// keyword (keyword_values.cpp).
std::vector<cli::KeywordArgument> KeywordArguments(const py::kwargs& kwargs);

// JSON as the Python objects json.loads gives (dict, list, str, numbers, None).
py::object ToPython(const nlohmann::json& j);

}  // namespace lfcam::python
