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
  s_scaled_ = slab.st.x_axis / slab.st.width_mm;
  t_scaled_ = slab.st.y_axis / slab.st.height_mm;
  s0_ = slab.st_domain.s0;
  s1_ = slab.st_domain.s1;
  t0_ = slab.st_domain.t0;
  t1_ = slab.st_domain.t1;
  s_to_k_ = n_s_ / slab.st_domain.s_extent();
  t_to_l_ = n_t_ / slab.st_domain.t_extent();
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c) camera_centers_.push_back(lf.camera_center(r, c));
}

}  // namespace lfcam
