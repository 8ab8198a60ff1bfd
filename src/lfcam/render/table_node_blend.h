#pragma once
// The cameras integrator's weights along a pixel row, blended from its table's nodes
// (render/camera_integrator.h, CameraIntegratorFrame::RowWeights), vectorised with Highway's
// dynamic dispatch. A row is cut into runs of pixels whose footprints share a table cell; within
// a run every pixel blends the same nodes, each with its own coefficients.
#include <cstddef>

namespace lfcam {

struct TableNodeRow {
  int cameras = 0, runs = 0;
  int nodes = 0;                   // nodes a cell (4, or 8 across two radius levels)
  const int* run_begin = nullptr;  // run r holds pixels [run_begin[r], run_begin[r + 1])
  // Per camera, the first and last run it is written over (-1: not written).
  const int* first_run = nullptr;
  const int* last_run = nullptr;
  // The nodes' weights of each camera in each run: values[(c * runs + r) * nodes + n].
  const float* values = nullptr;
  // Node n's coefficient for pixel i: coefficients[n * coefficient_stride + i]; readable a
  // vector (kTableNodeRowPadding floats) past the row's last pixel.
  const float* coefficients = nullptr;
  std::size_t coefficient_stride = 0;
};
inline constexpr std::size_t kTableNodeRowPadding = 64;

// For each camera c written and each run r from first_run[c] to last_run[c]:
// weights[c * stride + i] = sum over n of values[(c * runs + r) * nodes + n] * coefficients[n *
// coefficient_stride + i] for the run's pixels i, each product rounded and added in n's order
// from 0 (the scalar sum, to the last bit). Nothing else of `weights` is written.
void BlendTableNodes(const TableNodeRow& row, float* weights, std::size_t stride);

}  // namespace lfcam
