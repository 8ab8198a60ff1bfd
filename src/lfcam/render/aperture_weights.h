#pragma once
// The camera weights of the exact aperture integral (../shared/DESIGN.md, "The aperture
// integral"): with the focal-plane lookup, the paper's lens-sample estimator converges, as the
// lens sampling rate grows, to a weighted sum over the cameras under the aperture's footprint on
// the uv-plane, camera c weighted by the share of the footprint that its bilinear hat receives.
//
// Here in grid units: one camera pitch is 1, camera (col i, row j) sits at the integer point
// (i, j), and the PRP window is [-0.5, cols - 0.5] x [-0.5, rows - 0.5]. A camera's weight
// function along one axis is what the renderer's clamped bilinear lookup gives it: a tent of
// half-width 1 around it, held at 1 out to the window's edge for the outermost cameras (the
// lookup clamps there), nothing outside the window. Inside the window the weights of all
// cameras sum to 1, so a footprint's weights are normalised by the part of it inside the
// window: the lens points whose lines miss the window are not counted (as in the estimator).
//
// Each integral is exact up to Gauss-Legendre quadrature of smooth pieces: the disk is swept
// along x with x = cx + R sin(theta), the integral along y is closed form, and theta is split
// at every kink of the integrand (relative error below 1e-9).
#include <vector>

namespace lfcam {

struct GridCameraWeight {
  int col = 0, row = 0;
  double weight = 0;
};

// The integral over the disk of radius `radius` centred at (cx, cy) (grid units) of camera
// (col, row)'s weight function on a cols x rows grid.
double DiskCameraIntegral(double radius, double cx, double cy, int col, int row, int cols,
                          int rows);

// Every camera's share of the disk (those with a nonzero one), normalised to sum to 1; empty when
// the disk does not meet the window. A radius of 0 gives the bilinear weights at (cx, cy).
std::vector<GridCameraWeight> DiskCameraWeights(double radius, double cx, double cy, int cols,
                                                int rows);

}  // namespace lfcam
