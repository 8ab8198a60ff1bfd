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
#include "lfcam/render/depth_aware_sampler.h"

namespace lfcam::python {

namespace {

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
        const std::vector<cli::KeywordArgument> arguments = KeywordArguments(kwargs);
        cv::Mat image;
        {
          py::gil_scoped_release release;
          const auto request = cli::ParseRenderKeywords(arguments);
          const VirtualCamera camera = [&] {
            try {
              return request->camera.MakeCamera(*lf);
            } catch (const UsageError& e) {
              throw UsageError(cli::InKeywords(cli::RenderKeywordTable(), e.what()));
            }
          }();
          FrameRenderOptions options = request->options;
          DepthSet depth;
          if (options.interpolation == Interpolation::kDepth) {
            depth = request->render.depth.empty()
                        ? cli::EstimateDepthForFrames(*lf, {camera}, "", /*quiet=*/true)
                        : ReadDepthSet(request->render.depth, *lf,
                                       DepthsForRendering(DepthViewsNeeded(*lf, camera)));
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
      "render_keywords", [] { return cli::RenderKeywordTable().names(); },
      "The keywords lfcam.render takes.");
}

}  // namespace lfcam::python
