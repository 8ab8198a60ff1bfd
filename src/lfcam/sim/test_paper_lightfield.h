#pragma once
// Tests only: the reduced `paper` light field the fidelity measurements share (10 x 10 views of
// 416 x 384 st samples, 2 x 2 supersampled, 8-bit sRGB), simulated once per build and kept in
// the temporary directory for every test process (sim/test_capture.h: SharedTestArtifact).
#include "lfcam/core/lightfield_file.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/sim/simulate_lightfield.h"
#include "lfcam/sim/test_capture.h"

namespace lfcam::testing {

inline LightField SharedPaperLightField() {
  const auto dir = SharedTestArtifact("paper_lightfield", "paper.lf", [](const auto& out) {
    SimulateLightFieldOptions o;
    o.n_s = 416;
    o.n_t = 384;
    std::filesystem::create_directories(out);
    WriteLightField(SimulateLightField(MakePaperScene(), o), out / "paper.lf");
  });
  return ReadLightField(dir / "paper.lf");
}

// Every view's depth map of SharedPaperLightField(), estimated from it by the plane sweep with
// its defaults (`lfcam depth --all`), shared the same way.
inline DepthSet SharedPaperDepth(const LightField& lf) {
  const auto dir = SharedTestArtifact("paper_depth", "depth.json", [&](const auto& out) {
    DepthSet set(lf.dims());
    EstimateDepthSet(lf, set, [](int, int) { return true; }, {});
    WriteDepthSet(out, set, "paper.lf");
  });
  return ReadDepthSet(dir, lf);
}

}  // namespace lfcam::testing
