#pragma once
// How a light field's views sample the st-plane (docs/format.md): the one mapping between a
// point of the st-plane and a view's samples, which every path reads (the renderers' per-frame
// set-up and the GL shader's uniforms, the scalar sampler, the quadrilinear limit's prefilter,
// the depth lookup, depth, the focus probe, export) instead of computing it from the slab.
//
// A view's samples cover `domain` of the view window (window units, [0, 1]^2 = the window):
// sample (k, l) sits at window coordinates (s0 + (k + 0.5) / n_s * extent_s, t0 + ...), its
// centre at the integer point (k, l) of the continuous sample coordinates used below.
//
// Views share the light field's sampling (the slab's st domain, n_s x n_t: the reference grid)
// or each has its own window (format version 4): the reference grid moved by a whole number of
// samples, StOffset, so that a view's samples are still samples of the reference grid and sample
// (k, l) of view v is reference sample (k + offset.k, l + offset.l).
#include "lfcam/core/geometry.h"
#include "lfcam/core/slab.h"

namespace lfcam {

// A view's window: how many samples its grid is moved from the reference grid, along s and t.
struct StOffset {
  int k = 0, l = 0;
  bool operator==(const StOffset&) const = default;
};

struct StSampling {
  ViewWindow window;  // the st-plane's frame in the world and its unit square
  StDomain domain;    // what the samples cover, in window units (their outer edges)
  int n_s = 0, n_t = 0;

  double s_to_k() const { return n_s / domain.s_extent(); }  // samples per window unit
  double t_to_l() const { return n_t / domain.t_extent(); }
  double ds_mm() const { return domain.s_extent() / n_s * window.width_mm; }  // sample spacing
  double dt_mm() const { return domain.t_extent() / n_t * window.height_mm; }

  // Window coordinates of sample k (l): continuous, centres at integers.
  double s_of(double k) const { return domain.s0 + (k + 0.5) / n_s * domain.s_extent(); }
  double t_of(double l) const { return domain.t0 + (l + 0.5) / n_t * domain.t_extent(); }
  // Continuous sample coordinates of window coordinates (s, t) (not clamped).
  double k_of(double s) const { return (s - domain.s0) * s_to_k() - 0.5; }
  double l_of(double t) const { return (t - domain.t0) * t_to_l() - 0.5; }
  // The world point of sample (k, l), and the sample coordinates of a world point (projected
  // onto the plane along its normal).
  Vec3 Point(double k, double l) const { return window.point_at(s_of(k), t_of(l)); }
  Vec2 SampleOf(const Vec3& p) const {
    const Vec3 d = p - window.origin;
    return {k_of(window.x_axis.dot(d) / window.width_mm),
            l_of(window.y_axis.dot(d) / window.height_mm)};
  }
  // Whether window coordinates (s, t) lie in the sampled domain.
  bool Contains(double s, double t) const {
    return s >= domain.s0 && s <= domain.s1 && t >= domain.t0 && t <= domain.t1;
  }
  // The same sampling moved by whole samples (a view's own window).
  StSampling Moved(StOffset o) const {
    const double ds = o.k * domain.s_extent() / n_s, dt = o.l * domain.t_extent() / n_t;
    return {window, {domain.s0 + ds, domain.t0 + dt, domain.s1 + ds, domain.t1 + dt}, n_s, n_t};
  }
};

}  // namespace lfcam
