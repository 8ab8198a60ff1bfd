// The names of the integrators and lookups, as flags, view files and benchmark records spell
// them (declared beside their enums in cpu_renderer.h and lightfield_sampler.h; kept apart from
// the renderers so that the readers of those files build without them).
#include <fmt/format.h>

#include <utility>

#include "lfcam/core/error.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/depth_aware_sampler.h"
#include "lfcam/render/lightfield_sampler.h"

namespace lfcam {
namespace {

// One enum's values and their names, in the order an error lists them.
template <typename Enum, std::size_t N>
using Names = std::pair<Enum, const char*>[N];

template <typename Enum, std::size_t N>
std::string NameOf(const Names<Enum, N>& names, Enum value) {
  for (const auto& [v, name] : names)
    if (v == value) return name;
  return "?";
}

// The value named `name`; an unknown name throws, listing the names ("a, b or c").
template <typename Enum, std::size_t N>
Enum ValueNamed(const Names<Enum, N>& names, const std::string& name, const char* what) {
  std::string expected;
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i].second == name) return names[i].first;
    expected += i == 0 ? "" : i + 1 == N ? " or " : ", ";
    expected += names[i].second;
  }
  throw Error(fmt::format("unknown {} '{}' (expected {})", what, name, expected));
}

const Names<Integrator, 3> kIntegrators = {
    {Integrator::kLensSamples, "lens-samples"},
    {Integrator::kCameras, "cameras"},
    {Integrator::kCamerasQuadrilinear, "cameras-quadrilinear"}};
const Names<Interpolation, 3> kInterpolations = {{Interpolation::kQuadrilinear, "quadrilinear"},
                                                 {Interpolation::kFocalPlane, "focal-plane"},
                                                 {Interpolation::kDepth, "depth"}};
const Names<DepthBlend, 2> kDepthBlends = {{DepthBlend::kAgreeing, "agreeing"},
                                           {DepthBlend::kFourCameras, "four"}};

}  // namespace

std::string ToString(Integrator integrator) { return NameOf(kIntegrators, integrator); }
Integrator IntegratorFromString(const std::string& name) {
  return ValueNamed(kIntegrators, name, "integrator");
}

std::string ToString(Interpolation interpolation) { return NameOf(kInterpolations, interpolation); }
Interpolation InterpolationFromString(const std::string& name) {
  return ValueNamed(kInterpolations, name, "interpolation");
}

std::string ToString(DepthBlend blend) { return NameOf(kDepthBlends, blend); }
DepthBlend DepthBlendFromString(const std::string& name) {
  return ValueNamed(kDepthBlends, name, "depth blend");
}

}  // namespace lfcam
