#include "lfcam/render/lightfield_sampler.h"

#include <fmt/format.h>

#include "lfcam/core/error.h"

namespace lfcam {

LookupPlanes LookupPlanesOf(const LightField& lf) {
  LookupPlanes p;
  const Slab& slab = lf.slab();
  p.p_ca = slab.uv.p_ca;
  p.n_ca = slab.uv.n_ca;
  p.u_scaled = slab.uv.u_ca / slab.uv.width_mm();
  p.v_scaled = slab.uv.v_ca / slab.uv.height_mm();
  p.st_origin = slab.st.origin;
  p.n_st = slab.st.normal();
  const StSampling st = lf.st_sampling();
  p.s_scaled = st.window.x_axis / st.window.width_mm;
  p.t_scaled = st.window.y_axis / st.window.height_mm;
  p.s0 = st.domain.s0;
  p.t0 = st.domain.t0;
  p.s_to_k = st.s_to_k();
  p.t_to_l = st.t_to_l();
  const StDomain all = lf.st_union();
  p.u_s0 = all.s0;
  p.u_s1 = all.s1;
  p.u_t0 = all.t0;
  p.u_t1 = all.t1;
  return p;
}

LightFieldSampler::LightFieldSampler(const LightField& lf)
    : data_(lf.data()),
      srgb8_(lf.sample_type() == SampleType::kSrgb8),
      lut_(SrgbDecodeTable().data()),
      rows_(lf.dims().rows),
      cols_(lf.dims().cols),
      n_s_(lf.dims().n_s),
      n_t_(lf.dims().n_t),
      view_samples_(lf.dims().samples_per_view() * 3) {
  const LookupPlanes planes = LookupPlanesOf(lf);
  p_ca_ = planes.p_ca;
  n_ca_ = planes.n_ca;
  u_scaled_ = planes.u_scaled;
  v_scaled_ = planes.v_scaled;
  st_origin_ = planes.st_origin;
  n_st_ = planes.n_st;
  s_scaled_ = planes.s_scaled;
  t_scaled_ = planes.t_scaled;
  s0_ = planes.s0;
  t0_ = planes.t0;
  u_s0_ = planes.u_s0;
  u_s1_ = planes.u_s1;
  u_t0_ = planes.u_t0;
  u_t1_ = planes.u_t1;
  offsets_ = lf.st_offsets();
  s_to_k_ = planes.s_to_k;
  t_to_l_ = planes.t_to_l;
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c) camera_centers_.push_back(lf.camera_center(r, c));
}

}  // namespace lfcam
