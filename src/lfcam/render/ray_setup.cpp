#include "lfcam/render/ray_setup.h"

#include <limits>

#include "lfcam/core/color.h"

namespace lfcam {

OriginConstants SamplePlane::Origin(const Vec3& origin) const {
  OriginConstants c;
  c.num = float(n.dot(q - origin));
  c.n_o = float(n.dot(origin));
  c.x_o = float(a_x.dot(origin));
  c.y_o = float(a_y.dot(origin));
  c.x0 = float(a_x.dot(origin - q) + x_offset);
  c.y0 = float(a_y.dot(origin - q) + y_offset);
  return c;
}

PlaneAffines SamplePlane::Affines(const VirtualCamera& camera) const {
  // p_o is affine in (i, j): read it at three pixels.
  const Vec3 p00 = camera.focus_point(camera.pixel_direction(0, 0));
  const Vec3 p10 = camera.focus_point(camera.pixel_direction(1, 0));
  const Vec3 p01 = camera.focus_point(camera.pixel_direction(0, 1));
  const auto affine = [&](const Vec3& axis) {
    return PixelAffine{axis.dot(p00), axis.dot(p10 - p00), axis.dot(p01 - p00)};
  };
  return {affine(n), affine(a_x), affine(a_y)};
}

bool SamplePlane::Coordinates(const Vec3& origin, const Vec3& p, double* x, double* y) const {
  const double den = n.dot(p - origin);
  if (den == 0.0) return false;
  const Vec3 hit = origin + (n.dot(q - origin) / den) * (p - origin);
  *x = a_x.dot(hit - q) + x_offset;
  *y = a_y.dot(hit - q) + y_offset;
  return true;
}

SamplePlane UvSamplePlane(const LightField& lf) {
  const ArrayPlane& uv = lf.slab().uv;
  const int cols = lf.dims().cols, rows = lf.dims().rows;
  return {uv.p_ca, uv.n_ca, uv.u_ca * (cols / uv.width_mm()), uv.v_ca * (rows / uv.height_mm()),
          -0.5,    -0.5};
}

SamplePlane StSamplePlane(const LightField& lf) {
  const StSampling st = lf.st_sampling();
  const double s_to_k = st.s_to_k(), t_to_l = st.t_to_l();
  return {st.window.origin,
          st.window.normal(),
          st.window.x_axis * (s_to_k / st.window.width_mm),
          st.window.y_axis * (t_to_l / st.window.height_mm),
          -st.domain.s0 * s_to_k - 0.5,
          -st.domain.t0 * t_to_l - 0.5};
}

RaySetup::RaySetup(const LightField& lf, const VirtualCamera& camera, bool lens_samples)
    : samples(lf.data()),
      decode(SrgbDecodeTable().data()),
      rows(lf.dims().rows),
      cols(lf.dims().cols),
      n_s(lf.dims().n_s),
      n_t(lf.dims().n_t),
      view_bytes(static_cast<long long>(lf.view_bytes())),
      half_floats(lf.sample_type() == SampleType::kLinearF16),
      sample_bytes(half_floats ? 6 : 3),
      width(camera.width()),
      height(camera.height()) {
  const SamplePlane uv_plane = UvSamplePlane(lf), st_plane = StSamplePlane(lf);
  uv = uv_plane.Affines(camera);
  st = st_plane.Affines(camera);
  const LightField::SampleRange all = lf.st_union_samples();
  domain[0] = float(all.k0 - 0.5);
  domain[1] = float(all.l0 - 0.5);
  domain[2] = float(all.k1 + 0.5);
  domain[3] = float(all.l1 + 0.5);
  view_windows = lf.has_view_windows();
  if (lens_samples)
    for (const Vec2& disk : camera.lens_samples()) {
      const Vec3 lens = camera.lens_point(disk);
      lens_uv.push_back(uv_plane.Origin(lens));
      lens_st.push_back(st_plane.Origin(lens));
    }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const OriginConstants k = st_plane.Origin(lf.camera_center(r, c));
      const StOffset window = lf.st_offset(r, c);
      cam_num.push_back(k.num);
      cam_n_o.push_back(k.n_o);
      cam_x_o.push_back(k.x_o);
      cam_y_o.push_back(k.y_o);
      cam_x0.push_back(k.x0 - float(window.k));
      cam_y0.push_back(k.y0 - float(window.l));
      cam_k_offset.push_back(float(window.k));
      cam_l_offset.push_back(float(window.l));
    }
}

void RaySetup::SetTaper(const WindowTaper& window_taper) {
  taper = true;
  taper_h[0] = float(window_taper.h_k);
  taper_h[1] = float(window_taper.h_l);
  taper_window.clear();
  for (const std::array<float, 4>& w : window_taper.windows)
    taper_window.insert(taper_window.end(), w.begin(), w.end());
}

bool RowKernelsSupport(const LightField& lf) {
  const LightFieldDims& d = lf.dims();
  return (lf.sample_type() == SampleType::kSrgb8 || lf.sample_type() == SampleType::kLinearF16) &&
         d.n_s >= 2 && d.n_t >= 2 && d.rows >= 1 && d.cols >= 1;
}

bool FastKernelsSupport(const LightField& lf) {
  return RowKernelsSupport(lf) && lf.sample_type() == SampleType::kSrgb8 &&
         lf.total_bytes() < std::size_t(std::numeric_limits<std::int32_t>::max());
}

}  // namespace lfcam
