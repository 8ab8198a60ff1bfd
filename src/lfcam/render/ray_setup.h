#pragma once
// The per-frame ray set-up of the fast renderers: every coordinate a pixel's rays need, as
// projective functions of the pixel position, computed once per frame in double precision and
// handed to the per-pixel kernels in float (the vectorised CPU kernels now, the GL shader later).
//
// Every ray a renderer casts is a line from an origin O (the eye, a lens point or a camera
// centre) through the pixel's point in focus p_o. p_o is affine in the pixel position (i, j):
// p_o = e_c + d_o * direction, whose component along -n_c is 1. The line meets a plane
// (point q, normal n, in-plane coordinate axes a_x, a_y) at O + lambda (p_o - O) with
// lambda = n.(q - O) / n.(p_o - O), so its plane coordinate is
//   x = x_O + n.(q - O) * (a_x.p_o - a_x.O) / (n.p_o - n.O):
// three affine functions of (i, j) per plane (n.p_o, a_x.p_o, a_y.p_o), shared by every origin,
// and six constants per origin and plane. Coordinates are in sample units: on the uv-plane
// camera column and row (camera (col, row) at the integer point; the window is
// [-0.5, cols - 0.5] x [-0.5, rows - 0.5]); on the st-plane sample k and l of the reference grid
// (the sampled domain is [-0.5, n_s - 0.5] x [-0.5, n_t - 0.5] when the views share it, else the
// union of their windows). A camera's own lines (cam_*) are in that view's own samples: its
// window's offset is folded into cam_x0 and cam_y0.
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/virtual_camera.h"
#include "lfcam/render/window_taper.h"

namespace lfcam {

// value(i, j) = at00 + di * i + dj * j.
struct PixelAffine {
  double at00 = 0, di = 0, dj = 0;
  double at(double i, double j) const { return at00 + di * i + dj * j; }
};

// A plane's three affine functions of p_o.
struct PlaneAffines {
  PixelAffine n, x, y;  // n.p_o, a_x.p_o, a_y.p_o
};

// One origin's constants against one plane (float, as the kernels read them).
struct OriginConstants {
  float num = 0;           // n.(q - O)
  float n_o = 0;           // n.O
  float x_o = 0, y_o = 0;  // a_x.O, a_y.O
  float x0 = 0, y0 = 0;    // the plane coordinates of O itself
};

// A plane in sample units (see above).
struct SamplePlane {
  Vec3 q, n, a_x, a_y;
  double x_offset = 0, y_offset = 0;  // added to the coordinates (a_x.(X - q) + x_offset)

  OriginConstants Origin(const Vec3& origin) const;
  PlaneAffines Affines(const VirtualCamera& camera) const;
  // The plane coordinates of the line from `origin` through p (double precision; false when
  // the line runs parallel to the plane).
  bool Coordinates(const Vec3& origin, const Vec3& p, double* x, double* y) const;
};

SamplePlane UvSamplePlane(const LightField& lf);  // camera columns and rows
SamplePlane StSamplePlane(const LightField& lf);  // st samples k and l

// Everything the fast kernels read for one frame.
struct RaySetup {
  const std::uint8_t* samples = nullptr;  // the light field's; 4 readable bytes precede it
  const float* decode = nullptr;          // the 256-entry sRGB decoding table
  int rows = 0, cols = 0, n_s = 0, n_t = 0;
  long long view_bytes = 0;
  // Linear half floats (6 bytes a sample: only the row kernels read them) or 8-bit sRGB (3).
  bool half_floats = false;
  int sample_bytes = 3;
  int width = 0, height = 0;
  PlaneAffines uv, st;  // p_o against the uv- and st-planes
  // The sampled st domain in reference samples (lo_k, lo_l, hi_k, hi_l: the outer edges of the
  // union of the views' windows).
  float domain[4] = {0, 0, 0, 0};
  // Whether the views have their own windows: a read outside a view's window then adds nothing
  // and the blend renormalises over the views that hold the point; otherwise reads clamp.
  bool view_windows = false;
  std::vector<float> cam_k_offset, cam_l_offset;  // each view's window offset (per camera)
  std::vector<OriginConstants> lens_uv;           // per lens sample (the eye alone for a pinhole)
  std::vector<OriginConstants> lens_st;
  // Per camera (row-major), the st constants of its own lines, one array per field (the
  // kernels gather them by camera index).
  std::vector<float> cam_num, cam_n_o, cam_x_o, cam_y_o, cam_x0, cam_y0;
  // The cameras integrator's fade at the views' windows (render/window_taper.h; the quadrilinear
  // limit's): each camera's read weighs w times the share of its tent inside its window, in
  // place of the window's and the domain's hard edges. taper_window: 4 floats a camera (lo k,
  // lo l, hi k, hi l in its own samples).
  bool taper = false;
  float taper_h[2] = {0, 0};
  std::vector<float> taper_window;
  void SetTaper(const WindowTaper& window_taper);

  RaySetup(const LightField& lf, const VirtualCamera& camera, bool lens_samples);
  OriginConstants camera_st(int index) const {
    return {cam_num[index], cam_n_o[index], cam_x_o[index],
            cam_y_o[index], cam_x0[index],  cam_y0[index]};
  }
};

// Whether the vectorised kernels that read views a sample row at a time (the separable frame's,
// and the cameras integrator's rows) can read this light field: 8-bit sRGB or linear half
// floats, at least two samples and cameras along each axis, any size.
bool RowKernelsSupport(const LightField& lf);
// Whether the kernels that gather single samples can: 8-bit sRGB (each sample a 32-bit word's
// top three bytes) and byte offsets that fit 32 bits, as well. Otherwise the scalar reference
// renders what the row kernels cannot.
bool FastKernelsSupport(const LightField& lf);

}  // namespace lfcam
