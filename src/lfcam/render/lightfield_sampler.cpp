#include "lfcam/render/lightfield_sampler.h"

#include <fmt/format.h>

#include "lfcam/core/error.h"

namespace lfcam {

LightFieldSampler::LightFieldSampler(const LightField& lf)
    : data_(lf.data()),
      srgb8_(lf.sample_type() == SampleType::kSrgb8),
      lut_(SrgbDecodeTable().data()),
      rows_(lf.dims().rows),
      cols_(lf.dims().cols),
      n_s_(lf.dims().n_s),
      n_t_(lf.dims().n_t),
      view_samples_(lf.dims().samples_per_view() * 3) {
  const Slab& slab = lf.slab();
  p_ca_ = slab.uv.p_ca;
  n_ca_ = slab.uv.n_ca;
  u_scaled_ = slab.uv.u_ca / slab.uv.width_mm();
  v_scaled_ = slab.uv.v_ca / slab.uv.height_mm();
  st_origin_ = slab.st.origin;
  n_st_ = slab.st.normal();
  const StSampling st = lf.st_sampling();
  s_scaled_ = st.window.x_axis / st.window.width_mm;
  t_scaled_ = st.window.y_axis / st.window.height_mm;
  s0_ = st.domain.s0;
  t0_ = st.domain.t0;
  const StDomain all = lf.st_union();
  u_s0_ = all.s0;
  u_s1_ = all.s1;
  u_t0_ = all.t0;
  u_t1_ = all.t1;
  offsets_ = lf.st_offsets();
  s_to_k_ = st.s_to_k();
  t_to_l_ = st.t_to_l();
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c) camera_centers_.push_back(lf.camera_center(r, c));
}

}  // namespace lfcam
