// lfcam.render(lf, **camera): a view of a light field through the paper's virtual camera, with
// every flag of `lfcam render` as a keyword argument (cli/keyword_arguments.h), into an
// H x W x 3 array that owns the renderer's own image (no copy).
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <mutex>

#include "lfcam/cli/render_flags.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/python/bindings.h"

namespace lfcam::python {
namespace {

// A Python value as a keyword's value; anything else is a TypeError naming the keyword.
cli::KeywordValue KeywordValueOf(const std::string& name, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<long long>();
    } catch (const py::cast_error&) {
      throw UsageError(
          fmt::format("{}: {} is out of range", name, py::str(value).cast<std::string>()));
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__"))  // pathlib.Path: a file's name
    return py::str(value.attr("__fspath__")()).cast<std::string>();
  if (py::isinstance<py::sequence>(value) || py::hasattr(value, "__array__")) {
    std::vector<double> numbers;
    for (const py::handle item : py::iter(value)) {
      if (!py::isinstance<py::int_>(item) && !py::isinstance<py::float_>(item) &&
          !py::hasattr(item, "__float__"))
        throw py::type_error(fmt::format("{}: expected numbers, found {}", name,
                                         py::str(py::type::of(item)).cast<std::string>()));
      numbers.push_back(item.cast<double>());
      if (numbers.size() > 16) throw UsageError(fmt::format("{}: too many numbers", name));
    }
    return numbers;
  }
  throw py::type_error(fmt::format("{}: {} is not a value render takes", name,
                                   py::str(py::type::of(value)).cast<std::string>()));
}

// Renderers are opened once per backend and kept (a GL context is costly to make).
FrameRenderer& RendererFor(Backend backend) {
  static std::mutex mutex;
  static std::map<Backend, std::unique_ptr<FrameRenderer>> renderers;
  std::lock_guard lock(mutex);
  auto& renderer = renderers[backend];
  if (!renderer) renderer = cli::BackendFlags::Open(backend);
  return *renderer;
}

}  // namespace

void BindRender(py::module_& m) {
  m.def(
      "render",
      [](const std::shared_ptr<LightField>& lf, bool linear, const py::kwargs& kwargs) {
        std::vector<cli::KeywordArgument> arguments;
        for (const auto& [key, value] : kwargs) {
          const std::string name = py::str(key).cast<std::string>();
          arguments.push_back({name, KeywordValueOf(name, value)});
        }
        cv::Mat image;
        {
          py::gil_scoped_release release;
          const auto request = cli::ParseRenderKeywords(arguments);
          const VirtualCamera camera = [&] {
            try {
              return request->camera.MakeCamera(*lf);
            } catch (const UsageError& e) {
              throw UsageError(cli::InKeywords(e.what()));
            }
          }();
          FrameRenderOptions options = request->options;
          DepthSet depth;
          if (options.interpolation == Interpolation::kDepth) {
            depth = request->render.depth.empty()
                        ? cli::EstimateDepthForFrames(*lf, {camera}, "", /*quiet=*/true)
                        : ReadDepthSet(request->render.depth, *lf);
            options.depth = &depth;
            options.antialias = request->render.antialias;
          }
          const FrameRenderer& renderer = RendererFor(request->chosen_backend);
          RenderResult result = renderer.Render(*lf, camera, options);
          image = linear ? result.image : LinearToSrgb8Image(result.image);
        }
        return ArrayOfMat(image);
      },
      py::arg("lightfield"), py::kw_only(), py::arg("linear") = false,
      R"(Renders the light field through the virtual camera, as `lfcam render` does.

Keywords are render's flags without the dashes, with underscores: size (N or (W, H)),
eye, look_at, up ((x, y, z) world mm), focal_length, focus_distance, aperture, lens_rate,
no_breathing, camera (a saved view's JSON), as_camera ((row, col): the rig's camera),
integrator, interpolation, depth (a folder of `lfcam depth --all`), antialias, threads,
reference, backend ("cpu", "gl" or "auto"), workgroup. Their defaults are render's.

Returns an H x W x 3 array, top row first: uint8 sRGB, as `lfcam render` writes it, or with
linear=True float32 linear light. Raises lfcam.UsageError naming the keyword.)");
  m.def(
      "render_keywords", [] { return cli::RenderKeywords(); }, "The keywords lfcam.render takes.");
}

}  // namespace lfcam::python
