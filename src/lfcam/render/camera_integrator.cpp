#include "lfcam/render/camera_integrator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

#include "lfcam/render/table_node_blend.h"

namespace lfcam {
namespace {

constexpr double kRadiusStep = 1.0 / 16;  // between radius levels (grid units)
constexpr double kParallelTolerance = 1e-9;

}  // namespace

CameraIntegratorFrame::CameraIntegratorFrame(const LightField& lf, const VirtualCamera& camera,
                                             bool tabulate)
    : camera_(camera), rows_(lf.dims().rows), cols_(lf.dims().cols) {
  const ArrayPlane& uv = lf.slab().uv;
  pitch_ = uv.pitch_mm;
  p_ca_ = uv.p_ca;
  u_ca_ = uv.u_ca;
  v_ca_ = uv.v_ca;
  n_ca_ = uv.n_ca;
  exact_ = std::abs(n_ca_.dot(camera.u_c())) < kParallelTolerance &&
           std::abs(n_ca_.dot(camera.v_c())) < kParallelTolerance;
  // The pixel's direction is affine in (i, j), and so is d = e - p_o = -focus * direction.
  const double focus = camera.params().focus_distance_mm;
  const Vec3 d0 = -focus * camera.pixel_direction(0, 0);
  const Vec3 di = -focus * camera.pixel_direction(1, 0) - d0;
  const Vec3 dj = -focus * camera.pixel_direction(0, 1) - d0;
  const auto along = [&](const Vec3& axis) {
    return Affine{axis.dot(d0), axis.dot(di), axis.dot(dj)};
  };
  h_ = along(n_ca_);
  d_u_ = along(u_ca_);
  d_v_ = along(v_ca_);
  d_lens_ = along(camera.u_c().cross(camera.v_c()).normalized());
  c0_ = n_ca_.dot(p_ca_ - camera.e_c());
  e_u_ = (camera.e_c() - p_ca_).dot(u_ca_);
  e_v_ = (camera.e_c() - p_ca_).dot(v_ca_);
  lens_radius_ = 0.5 * camera.params().aperture_mm;

  // The eye on the array's plane with the lens parallel to it: every footprint is the lens.
  if (exact_ && std::abs(n_ca_.dot(camera.e_c() - p_ca_)) < kParallelTolerance * pitch_) {
    const Footprint f = FootprintOf(0, 0);
    if (f.valid) {
      uniform_ = DiskCameraWeights(f.radius, f.cx, f.cy, cols_, rows_);
      if (!uniform_.empty()) return;
    }
  }
  if (!tabulate) return;
  // Every pixel's footprint: the range of centres and radii the table must cover.
  struct Range {
    double r_lo = 1e300, r_hi = -1e300, x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
    void Add(const Range& o) {
      r_lo = std::min(r_lo, o.r_lo);
      r_hi = std::max(r_hi, o.r_hi);
      x_lo = std::min(x_lo, o.x_lo);
      x_hi = std::max(x_hi, o.x_hi);
      y_lo = std::min(y_lo, o.y_lo);
      y_hi = std::max(y_hi, o.y_hi);
    }
  };
  const Range range = tbb::parallel_reduce(
      tbb::blocked_range<int>(0, camera.height()), Range{},
      [&](const tbb::blocked_range<int>& rows, Range r) {
        for (int j = rows.begin(); j != rows.end(); ++j)
          for (int i = 0; i < camera.width(); ++i) {
            const Footprint f = FootprintOf(i, j);
            if (!f.valid) continue;
            // Centres farther than the radius plus a pitch from the window have no weights.
            if (FarFromWindow(f.cx, f.cy, f.radius, cols_, rows_)) continue;
            r.Add({f.radius, f.radius, f.cx, f.cx, f.cy, f.cy});
          }
        return r;
      },
      [](Range a, const Range& b) {
        a.Add(b);
        return a;
      });
  const double r_lo = range.r_lo, r_hi = range.r_hi, x_lo = range.x_lo, x_hi = range.x_hi,
               y_lo = range.y_lo, y_hi = range.y_hi;
  if (r_lo > r_hi) return;  // no pixel reaches the array
  if (exact_ && x_hi - x_lo < 1e-9 && y_hi - y_lo < 1e-9 && r_hi - r_lo < 1e-9) {
    uniform_ = DiskCameraWeights(r_lo, x_lo, y_lo, cols_, rows_);
    if (!uniform_.empty()) return;
  }
  const std::size_t cameras = std::size_t(rows_) * std::size_t(cols_);
  levels_ = TableLayout(r_lo, r_hi, x_lo, x_hi, y_lo, y_hi);
  for (Level& level : levels_) {
    level.weights.assign(std::size_t(level.nx) * std::size_t(level.ny) * cameras, 0.0f);
    level.totals.assign(std::size_t(level.nx) * std::size_t(level.ny), 0.0f);
  }
  for (Level& level : levels_)
    tbb::parallel_for(0, level.nx * level.ny, [&](int node) {
      const int a = node % level.nx, b = node / level.nx;
      const double cx = double(level.x0 + a) / kNodesPerPitch,
                   cy = double(level.y0 + b) / kNodesPerPitch;
      float* out = level.weights.data() + std::size_t(node) * cameras;
      for (const GridCameraWeight& w : DiskCameraWeights(level.radius, cx, cy, cols_, rows_))
        out[std::size_t(w.row * cols_ + w.col)] = float(w.weight);
      float total = 0.0f;
      for (std::size_t c = 0; c < cameras; ++c) total += out[c];
      level.totals[std::size_t(node)] = total;
    });
}

std::vector<CameraIntegratorFrame::Level> CameraIntegratorFrame::TableLayout(
    double r_lo, double r_hi, double x_lo, double x_hi, double y_lo, double y_hi) {
  std::vector<double> radii;
  if (r_hi - r_lo < 1e-9) {
    radii = {r_lo};
  } else {
    const int steps = std::max(1, int(std::ceil((r_hi - r_lo) / kRadiusStep)));
    for (int k = 0; k <= steps; ++k) radii.push_back(r_lo + (r_hi - r_lo) * k / steps);
  }
  const int x0 = int(std::floor(x_lo * kNodesPerPitch)) - 1,
            x1 = int(std::ceil(x_hi * kNodesPerPitch)) + 1;
  const int y0 = int(std::floor(y_lo * kNodesPerPitch)) - 1,
            y1 = int(std::ceil(y_hi * kNodesPerPitch)) + 1;
  std::vector<Level> levels;
  for (const double radius : radii) {
    Level level;
    level.radius = radius;
    level.x0 = x0;
    level.y0 = y0;
    level.nx = x1 - x0 + 1;
    level.ny = y1 - y0 + 1;
    levels.push_back(std::move(level));
  }
  return levels;
}

Footprint CameraIntegratorFrame::FootprintOf(int i, int j) const {
  // The lens disk projected from p_o onto the uv-plane: U(x) = p_o + lambda(x) (x - p_o), with
  // lambda(x) = n.(p_ca - p_o) / n.(x - p_o). Its centre, U(e), is (e - p_ca) + (c0 / h) d in
  // the array's frame (lambda(e) = 1 + c0 / h); and a central projection from p_o scales areas
  // by lambda^2 times the cosines' ratio, (n_lens.d) / (n.d), so the disk of the same area has
  // radius r |lambda| sqrt((n_lens.d) / h).
  Footprint f;
  const double h = h_.At(i, j);
  if (std::abs(h) < 1e-12) return f;
  const double q = c0_ / h;
  f.cx = (e_u_ + q * d_u_.At(i, j)) / pitch_ - 0.5;
  f.cy = (e_v_ + q * d_v_.At(i, j)) / pitch_ - 0.5;
  f.radius = lens_radius_ * std::abs(1.0 + q) * std::sqrt(std::abs(d_lens_.At(i, j) / h)) / pitch_;
  f.valid = std::isfinite(f.cx) && std::isfinite(f.cy) && std::isfinite(f.radius);
  return f;
}

bool CameraIntegratorFrame::CellUnnormalised(const Footprint& f, TableCell* cell,
                                             float coefficients[8]) const {
  if (!f.valid || levels_.empty()) return false;
  // A footprint that does not meet the window has no weights (its lattice neighbours may).
  const double dx = std::max({-0.5 - f.cx, f.cx - (cols_ - 0.5), 0.0});
  const double dy = std::max({-0.5 - f.cy, f.cy - (rows_ - 0.5), 0.0});
  if (dx * dx + dy * dy >= f.radius * f.radius && (dx > 0 || dy > 0)) return false;
  const bool two = levels_.size() > 1;
  int k = 0;
  float t = 0.0f;
  if (two) {
    // Linear between the two radius levels around the footprint's.
    const double step = levels_[1].radius - levels_[0].radius;
    const double x =
        std::clamp((f.radius - levels_[0].radius) / step, 0.0, double(levels_.size() - 1));
    k = std::min(int(x), int(levels_.size()) - 2);
    t = float(x - k);
  }
  // Bilinear in the lattice, the same at every level (TableLayout).
  const Level& level = levels_[std::size_t(k)];
  const double x = f.cx * kNodesPerPitch - level.x0, y = f.cy * kNodesPerPitch - level.y0;
  const int a = int(std::floor(x)), b = int(std::floor(y));
  const float fx = float(x - a), fy = float(y - b);
  *cell = {k, a, b};
  const float w0 = two ? 1 - t : 1.0f;
  coefficients[0] = w0 * (1 - fx) * (1 - fy), coefficients[1] = w0 * fx * (1 - fy);
  coefficients[2] = w0 * (1 - fx) * fy, coefficients[3] = w0 * fx * fy;
  if (two) {
    coefficients[4] = t * (1 - fx) * (1 - fy), coefficients[5] = t * fx * (1 - fy);
    coefficients[6] = t * (1 - fx) * fy, coefficients[7] = t * fx * fy;
  }
  return true;
}

void CameraIntegratorFrame::Renormalise(const float totals[8], float coefficients[8]) const {
  // Next to the window's edge a lattice neighbour may miss the window (no weights) while the
  // footprint itself meets it. The blend's sum is the nodes' sums blended.
  float total = 0.0f;
  for (int n = 0; n < NodesPerCell(); ++n) total += coefficients[n] * totals[n];
  if (total > 0.0f) {
    const float scale = 1.0f / total;
    for (int n = 0; n < NodesPerCell(); ++n) coefficients[n] *= scale;
  }
}

bool CameraIntegratorFrame::CellOf(const Footprint& f, TableCell* cell,
                                   float coefficients[8]) const {
  if (!CellUnnormalised(f, cell, coefficients)) return false;
  float totals[8];
  for (int n = 0; n < NodesPerCell(); ++n) totals[n] = NodeTotal(*cell, n);
  Renormalise(totals, coefficients);
  return true;
}

std::size_t CameraIntegratorFrame::NodeIndex(const TableCell& cell, int n) const {
  const Level& level = levels_[std::size_t(cell.k + n / 4)];
  const int a = std::clamp(cell.a + n % 2, 0, level.nx - 1);
  const int b = std::clamp(cell.b + (n / 2) % 2, 0, level.ny - 1);
  return std::size_t(b) * std::size_t(level.nx) + std::size_t(a);
}

float CameraIntegratorFrame::NodeTotal(const TableCell& cell, int n) const {
  return levels_[std::size_t(cell.k + n / 4)].totals[NodeIndex(cell, n)];
}

void CameraIntegratorFrame::NodesOf(const TableCell& cell, const float* nodes[8]) const {
  const std::size_t cameras = std::size_t(rows_) * std::size_t(cols_);
  for (int n = 0; n < NodesPerCell(); ++n)
    nodes[n] = levels_[std::size_t(cell.k + n / 4)].weights.data() + NodeIndex(cell, n) * cameras;
}

void CameraIntegratorFrame::Weights(const Footprint& f, float* weights) const {
  const std::size_t cameras = std::size_t(rows_) * std::size_t(cols_);
  std::fill(weights, weights + cameras, 0.0f);
  if (!f.valid) return;
  if (!uniform_.empty()) {
    for (const GridCameraWeight& c : uniform_)
      weights[std::size_t(c.row * cols_ + c.col)] = float(c.weight);
    return;
  }
  TableCell cell;
  float coefficients[8];
  if (!CellOf(f, &cell, coefficients)) return;
  const float* nodes[8];
  NodesOf(cell, nodes);
  for (int n = 0; n < NodesPerCell(); ++n)
    for (std::size_t c = 0; c < cameras; ++c) weights[c] += coefficients[n] * nodes[n][c];
}

void CameraIntegratorFrame::RowWeights(int j, int width, std::size_t stride, float* weights,
                                       std::vector<int>* cameras_used,
                                       std::vector<std::pair<int, int>>* spans) const {
  const std::size_t cameras = std::size_t(rows_) * std::size_t(cols_);
  cameras_used->clear();
  if (spans != nullptr) spans->clear();
  if (levels_.empty()) return;
  // Each pixel's table cell (k = -1: no weights) and its nodes' coefficients, node n's for
  // pixel i at coefficients[n * w + i], so that the loops over the pixels run along contiguous
  // memory (a vector of padding past the last node's row for the blend's loads).
  const int nodes = NodesPerCell();
  const std::size_t w = std::size_t(width);
  // (CellOf's, its nodes' sums read once for each run of pixels in one cell.)
  std::vector<TableCell> cells(w);
  std::vector<float> coefficients(w * std::size_t(nodes) + kTableNodeRowPadding);
  TableCell totals_cell;  // k = -1: none yet
  float totals[8] = {};
  for (int i = 0; i < width; ++i) {
    float c[8];
    TableCell& cell = cells[std::size_t(i)];
    if (!CellUnnormalised(FootprintOf(i, j), &cell, c)) continue;
    if (!(cell == totals_cell)) {
      for (int n = 0; n < nodes; ++n) totals[n] = NodeTotal(cell, n);
      totals_cell = cell;
    }
    Renormalise(totals, c);
    for (int n = 0; n < nodes; ++n) coefficients[std::size_t(n) * w + std::size_t(i)] = c[n];
  }
  // The row's runs of pixels sharing a cell.
  std::vector<int> run_begin;
  for (int i = 0; i < width; ++i)
    if (i == 0 || !(cells[std::size_t(i)] == cells[std::size_t(i - 1)])) run_begin.push_back(i);
  const int runs = int(run_begin.size());
  run_begin.push_back(width);
  // Each camera's nodes' weights in each run, and its first and last run whose nodes weigh it:
  // it is written over those runs and every run between them (zeros where its nodes weigh
  // nothing), so a caller reads no stale weights there. A camera is listed where a node that
  // weighs it has a coefficient above 0 at some pixel of the run (the blend's sum of products,
  // none negative, is then above 0).
  constexpr int kNone = -1;
  std::vector<int> first_run(cameras, kNone), last_run(cameras, kNone);
  std::vector<char> used(cameras, 0);
  std::vector<float> values(cameras * std::size_t(runs) * std::size_t(nodes), 0.0f);
  for (int run = 0; run < runs; ++run) {
    const TableCell cell = cells[std::size_t(run_begin[std::size_t(run)])];
    if (cell.k < 0) continue;
    bool weighs[8] = {};
    for (int n = 0; n < nodes; ++n)
      for (int i = run_begin[std::size_t(run)]; i < run_begin[std::size_t(run) + 1]; ++i)
        weighs[n] |= coefficients[std::size_t(n) * w + std::size_t(i)] != 0.0f;
    const float* node[8];
    NodesOf(cell, node);
    for (std::size_t c = 0; c < cameras; ++c) {
      float* v = values.data() + (c * std::size_t(runs) + std::size_t(run)) * std::size_t(nodes);
      bool any = false;
      for (int n = 0; n < nodes; ++n) {
        v[n] = node[n][c];
        any |= v[n] != 0.0f;
        used[c] |= v[n] != 0.0f && weighs[n];
      }
      if (!any) continue;
      if (first_run[c] == kNone) first_run[c] = run;
      last_run[c] = run;
    }
  }
  TableNodeRow row;
  row.cameras = int(cameras);
  row.runs = runs;
  row.nodes = nodes;
  row.run_begin = run_begin.data();
  row.first_run = first_run.data();
  row.last_run = last_run.data();
  row.values = values.data();
  row.coefficients = coefficients.data();
  row.coefficient_stride = w;
  BlendTableNodes(row, weights, stride);
  for (std::size_t c = 0; c < cameras; ++c) {
    if (!used[c]) continue;
    cameras_used->push_back(int(c));
    if (spans != nullptr)
      spans->emplace_back(run_begin[std::size_t(first_run[c])],
                          run_begin[std::size_t(last_run[c]) + 1]);
  }
}

std::vector<bool> CameraIntegratorFrame::CamerasRead() const {
  const std::size_t cameras = std::size_t(rows_) * std::size_t(cols_);
  std::vector<bool> read(cameras, false);
  for (const GridCameraWeight& c : uniform_) read[std::size_t(c.row * cols_ + c.col)] = true;
  for (const Level& level : levels_)
    for (std::size_t i = 0; i < level.weights.size(); ++i)
      if (level.weights[i] > 0.0f) read[i % cameras] = true;
  return read;
}

std::size_t CameraIntegratorFrame::table_nodes() const {
  std::size_t n = 0;
  for (const Level& level : levels_) n += std::size_t(level.nx) * std::size_t(level.ny);
  return n;
}

}  // namespace lfcam
