// The names of the integrators and lookups, as flags, view files and benchmark records spell
// them (declared beside their enums in cpu_renderer.h and lightfield_sampler.h; kept apart from
// the renderers so that the readers of those files build without them).
#include <fmt/format.h>

#include "lfcam/core/error.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/depth_aware_sampler.h"
#include "lfcam/render/lightfield_sampler.h"

namespace lfcam {

std::string ToString(Integrator integrator) {
  switch (integrator) {
    case Integrator::kLensSamples:
      return "lens-samples";
    case Integrator::kCameras:
      return "cameras";
    case Integrator::kCamerasQuadrilinear:
      return "cameras-quadrilinear";
  }
  return "?";
}

Integrator IntegratorFromString(const std::string& name) {
  if (name == "lens-samples") return Integrator::kLensSamples;
  if (name == "cameras") return Integrator::kCameras;
  if (name == "cameras-quadrilinear") return Integrator::kCamerasQuadrilinear;
  throw Error(fmt::format(
      "unknown integrator '{}' (expected lens-samples, cameras or cameras-quadrilinear)", name));
}

std::string ToString(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::kQuadrilinear:
      return "quadrilinear";
    case Interpolation::kFocalPlane:
      return "focal-plane";
    case Interpolation::kDepth:
      return "depth";
  }
  return "?";
}

Interpolation InterpolationFromString(const std::string& name) {
  if (name == "quadrilinear") return Interpolation::kQuadrilinear;
  if (name == "focal-plane") return Interpolation::kFocalPlane;
  if (name == "depth") return Interpolation::kDepth;
  throw Error(fmt::format(
      "unknown interpolation '{}' (expected quadrilinear, focal-plane or depth)", name));
}

std::string ToString(DepthBlend blend) {
  switch (blend) {
    case DepthBlend::kFourCameras:
      return "four";
    case DepthBlend::kAgreeing:
      return "agreeing";
  }
  return "?";
}

DepthBlend DepthBlendFromString(const std::string& name) {
  if (name == "four") return DepthBlend::kFourCameras;
  if (name == "agreeing") return DepthBlend::kAgreeing;
  throw Error(fmt::format("unknown depth blend '{}' (expected agreeing or four)", name));
}

}  // namespace lfcam
