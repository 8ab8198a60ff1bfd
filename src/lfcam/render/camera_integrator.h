#pragma once
// The cameras integrator (`lfcam render --integrator cameras`): the limit, as the lens sampling
// rate grows, of the paper's lens-sample estimator with the focal-plane lookup
// (../shared/DESIGN.md, "The aperture integral"). Each camera under the aperture's footprint on
// the uv-plane is read once, along its own ray through the pixel's point in focus p_o, weighted
// by the share of the footprint its bilinear hat receives (render/aperture_weights.h). No lens
// samples: noise-free, no lens-sample aliasing, the cost grows with the cameras under the
// aperture.
//
// The footprint is the lens disk projected through p_o onto the uv-plane. When the lens is
// parallel to the array (the camera looks along -n_ca, wherever the eye is) it is a disk, and
// the weights are exact. A lens turned away from the array's plane projects to a slightly
// elliptical (projective) footprint, taken here as the disk of the same area at the same
// centre: close, not exact (the tests measure the gap).
//
// The weights are tabulated once per frame on a lattice of footprint centres (8 a pitch) and
// radii, over the part of the lattice the frame's pixels reach, and interpolated between.
#include <utility>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/aperture_weights.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

// Where one pixel's aperture footprint lies on the uv-plane, in grid units (camera (col, row)
// at the integer point (col, row)).
struct Footprint {
  double cx = 0, cy = 0, radius = 0;
  bool valid = false;  // false when the lens's lines through p_o run parallel to the array
};

class CameraIntegratorFrame {
 public:
  // Sets up the frame: every pixel's footprint, and the weights for all of them. `camera` must
  // outlive the frame. With `tabulate` false only the uniform case is set up (the eye on the
  // array's plane); a frame that needs the table then has none (the GL renderer builds it on the
  // GPU: needs_table()).
  CameraIntegratorFrame(const LightField& lf, const VirtualCamera& camera, bool tabulate = true);

  // Pixel (i, j)'s footprint (j bottom-up, as VirtualCamera counts).
  Footprint FootprintOf(int i, int j) const;
  // The weights of every camera (row-major, rows x cols) for a footprint; sums to 1, or all 0
  // when the footprint misses the window.
  void Weights(const Footprint& footprint, float* weights) const;
  // The weights of every pixel of row j (0 <= i < width), the numbers Weights gives for each
  // pixel's footprint, camera-major: camera c's for pixel i at weights[c * stride + i]. Only the
  // cameras with a weight somewhere in the row are listed in `cameras`, ascending, and with
  // `spans`, the pixels [begin, end) written for each (every pixel it has a weight at, and zeros
  // between); the rest of the row is left as it was. Pixels whose footprints share a table cell
  // are weighted together, camera by camera across them, where Weights adds each node's whole
  // vector to one pixel.
  void RowWeights(int j, int width, std::size_t stride, float* weights, std::vector<int>* cameras,
                  std::vector<std::pair<int, int>>* spans = nullptr) const;

  bool exact() const { return exact_; }  // the lens is parallel to the array
  // The frame's footprints differ from pixel to pixel, so its weights come from a table (built
  // here unless the constructor was told not to).
  bool needs_table() const { return uniform_.empty(); }
  // When every pixel has the same footprint (the eye on the array's plane, looking along its
  // normal: each footprint is the lens itself), its cameras and weights, else empty.
  const std::vector<GridCameraWeight>& uniform_weights() const { return uniform_; }
  std::size_t table_nodes() const;  // footprint centres tabulated, over all radii
  // Whether some pixel of the frame gives camera (row * cols + col) a weight (a superset: every
  // camera with a weight at a tabulated footprint).
  std::vector<bool> CamerasRead() const;

  // The table (for the GL renderer, which interpolates it per pixel as Weights does): radius
  // levels, each a lattice of footprint centres (the same lattice at every level) with a dense
  // weight vector per node.
  static constexpr int kNodesPerPitch = 8;
  struct Level {
    double radius = 0;
    int x0 = 0, y0 = 0, nx = 0, ny = 0;  // node (a, b) at ((x0 + a), (y0 + b)) / kNodesPerPitch
    std::vector<float> weights;          // [b][a][camera, row-major]: nx * ny * rows * cols
    std::vector<float> totals;           // [b][a]: each node's weights summed (1, or 0 off the
                                         // window), in the cameras' order
  };
  const std::vector<Level>& levels() const { return levels_; }
  // The table's layout (levels without weights) for footprints whose radii span [r_lo, r_hi] and
  // centres [x_lo, x_hi] x [y_lo, y_hi] (grid units): radius levels kRadiusStep apart or closer,
  // a lattice kNodesPerPitch a pitch with a node of margin. The CPU's table and the GPU's share it.
  static std::vector<Level> TableLayout(double r_lo, double r_hi, double x_lo, double x_hi,
                                        double y_lo, double y_hi);
  // Whether a footprint centred at (cx, cy) with `radius` is too far from a cols x rows window
  // to have weights (farther than its radius and a pitch): the table leaves it out.
  static bool FarFromWindow(double cx, double cy, double radius, int cols, int rows) {
    return cx < -1.5 - radius || cx > cols + 0.5 + radius || cy < -1.5 - radius ||
           cy > rows + 0.5 + radius;
  }

 private:
  const VirtualCamera& camera_;
  int rows_, cols_;
  double pitch_;
  Vec3 p_ca_, u_ca_, v_ca_, n_ca_;
  bool exact_ = true;
  // FootprintOf's terms, each affine in the pixel's (i, j): a + b i + c j. With d = e - p_o (the
  // eye less the pixel's point in focus, affine since the focal plane is a plane), h = n_ca.d,
  // d.u_ca, d.v_ca and n_lens.d; and the constants c0 = n_ca.(p_ca - e), (e - p_ca).u_ca and
  // (e - p_ca).v_ca.
  struct Affine {
    double a = 0, b = 0, c = 0;
    double At(int i, int j) const { return a + b * i + c * j; }
  };
  Affine h_, d_u_, d_v_, d_lens_;
  double c0_ = 0, e_u_ = 0, e_v_ = 0, lens_radius_ = 0;
  std::vector<Level> levels_;  // increasing radius
  std::vector<GridCameraWeight> uniform_;

  // Where a footprint's weights come from in the table: its lower radius level k and lattice
  // node (a, b), and the coefficients of the cell's nodes (4, or 8 across two levels), in the
  // order Weights adds them. False when the footprint has no weights (invalid, or missing the
  // window).
  struct TableCell {
    int k = -1, a = 0, b = 0;
    bool operator==(const TableCell& o) const { return k == o.k && a == o.a && b == o.b; }
  };
  // The coefficients are normalised: the cell's nodes' weights, added with them, sum to 1 (a
  // node off the window adds none).
  bool CellOf(const Footprint& footprint, TableCell* cell, float coefficients[8]) const;
  // CellOf in two steps: the cell and its coefficients as the lattice gives them, then scaled
  // by the cell's nodes' sums (`totals`, NodeTotal's in the nodes' order).
  bool CellUnnormalised(const Footprint& footprint, TableCell* cell, float coefficients[8]) const;
  void Renormalise(const float totals[8], float coefficients[8]) const;
  int NodesPerCell() const { return levels_.size() > 1 ? 8 : 4; }
  // The weight vectors of the cell's nodes (clamped to the lattice), in the same order.
  void NodesOf(const TableCell& cell, const float* nodes[8]) const;
  // Node n of the cell (clamped to the lattice): its index in its level, and its weights' sum.
  std::size_t NodeIndex(const TableCell& cell, int n) const;
  float NodeTotal(const TableCell& cell, int n) const;
};

}  // namespace lfcam
