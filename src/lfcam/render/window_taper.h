#pragma once
// The quadrilinear limit's fade at a view's edge (render/quadrilinear_limit.h). The limit reads
// camera c through its bilinear hat scaled onto the st-plane: a tent of half-width h samples
// around the point where c's own line through p_o meets the plane. The lens samples it is the
// limit of drop, ray by ray, those whose st point leaves the view's window (or, where the views
// share one, the sampled domain), so in the limit the camera counts by the share of its tent
// inside its window: it fades out over 2h samples as its line leaves the window. A hard edge
// (the focal-plane reads' own, h 0) drops the camera whole instead, and where a strongly
// defocused frame reaches the views' edges the blend steps from row to row (bands).
//
// Every path of the limit reads the taper from here: the scalar reference (RenderPixelCameras),
// the row kernels, the separable frame and the GL shader (render_frame.comp's twin).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace lfcam {

// The share of a tent of half-width h centred at x that lies in [lo, hi]; with h 0, 1 inside
// (both ends included) and 0 outside: the hard edge.
inline double TentShareInside(double x, double lo, double hi, double h) {
  if (!(h > 0)) return x >= lo && x <= hi ? 1.0 : 0.0;
  // The tent's distribution function at z half-widths from its centre.
  const auto below = [](double z) {
    z = std::clamp(z, -1.0, 1.0);
    return 0.5 + z - 0.5 * z * std::abs(z);
  };
  return std::max(0.0, below((hi - x) / h) + below((x - lo) / h) - 1.0);
}

struct WindowTaper {
  // The tent's half-widths in the rendered light field's samples along s and t (0: a hard edge).
  double h_k = 0, h_l = 0;
  // Per camera (row-major), its view's window in that view's own sample coordinates (the
  // coordinates its focal-plane read is in; the outer edges: lo k, lo l, hi k, hi l). For the
  // views as stored, [-0.5, n - 0.5] along each axis (the sampled domain where views share it);
  // a copy kept every m samples (PrefilteredCopy) overhangs the windows of the views it was
  // filtered from, and carries theirs here.
  std::vector<std::array<float, 4>> windows;

  bool active() const { return !windows.empty(); }
  // Camera `index`'s share at its own sample coordinates (k, l).
  double Share(int index, double k, double l) const {
    const std::array<float, 4>& w = windows[std::size_t(index)];
    return TentShareInside(k, w[0], w[2], h_k) * TentShareInside(l, w[1], w[3], h_l);
  }
};

}  // namespace lfcam
