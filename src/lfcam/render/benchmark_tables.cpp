#include "lfcam/render/benchmark_tables.h"

#include <tbb/info.h>

#include <algorithm>
#include <chrono>

namespace lfcam {
namespace {

struct Table1Row {
  int size;
  double cpu_ms, gpu_ms;  // the paper's one-thread CPU and its fastest GPU work group (16, 8)
};
constexpr Table1Row kTable1[] = {
    {768, 289.84, 1.34}, {1024, 510.41, 1.53}, {1536, 1149.38, 2.73}, {2048, 2023.93, 3.87}};

constexpr double kTable2Apertures[] = {64, 128, 192, 256};
constexpr double kTable2Rates[] = {1, 2, 4, 9, 16};
// The paper's GPU milliseconds, rows d_l, columns gamma.
constexpr double kTable2[4][5] = {{2.67, 4.83, 6.06, 11.74, 19.41},
                                  {4.22, 6.62, 11.56, 23.38, 40.82},
                                  {6.04, 10.38, 18.33, 39.25, 64.06},
                                  {7.81, 14.01, 25.88, 60.61, 87.38}};

}  // namespace

std::vector<BenchCell> Table1Cells() {
  std::vector<BenchCell> cells;
  for (const Table1Row& row : kTable1)
    for (const int threads : {1, 0}) {
      BenchCell c;
      c.table = "table1";
      c.size = row.size;
      c.threads = threads;
      c.paper_ms = row.cpu_ms;
      c.paper_gpu_ms = row.gpu_ms;
      cells.push_back(c);
    }
  return cells;
}

std::vector<BenchCell> Table2Cells(Integrator integrator, Interpolation interpolation) {
  std::vector<BenchCell> cells;
  for (int a = 0; a < 4; ++a)
    for (int g = 0; g < 5; ++g) {
      // The cameras integrators (the limits): gamma plays no part, one cell per aperture.
      if (integrator != Integrator::kLensSamples && g != 4) continue;
      BenchCell c;
      c.table = "table2";
      c.size = 1024;
      c.integrator = integrator;
      c.interpolation = integrator == Integrator::kCameras ? Interpolation::kFocalPlane
                        : integrator == Integrator::kCamerasQuadrilinear
                            ? Interpolation::kQuadrilinear
                            : interpolation;
      c.aperture_mm = kTable2Apertures[a];
      if (integrator == Integrator::kLensSamples) c.lens_rate = kTable2Rates[g];
      c.focal_length_mm = 444;
      c.focus_distance_mm = 4000;
      c.paper_ms = kTable2[a][g];
      cells.push_back(c);
    }
  return cells;
}

VirtualCameraParams CellCamera(const BenchCell& cell, const ArrayPlane& array) {
  VirtualCameraParams p;
  p.width = p.height = cell.size;
  p.eye = array.center();
  p.look_at = p.eye - 1000.0 * array.n_ca;
  p.up = array.v_ca;
  p.focal_length_mm = cell.focal_length_mm;
  p.focus_distance_mm = cell.focus_distance_mm;
  p.aperture_mm = cell.aperture_mm;
  p.lens_rate = cell.lens_rate.value_or(4.0);
  return p;
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

Timing TimeCell(const LightField& lf, const BenchCell& cell, const FrameRenderer& renderer,
                FrameRenderOptions options, const TimingPolicy& policy) {
  const VirtualCamera camera(CellCamera(cell, lf.slab().uv));
  options.threads = cell.threads;
  options.integrator = cell.integrator;
  options.interpolation = cell.interpolation;
  Timing timing;
  // Warm-up: caches; on the GPU also the upload, the shader's compilation and the clocks.
  for (int i = 0; i < (renderer.uses_gl() ? 3 : 1); ++i)
    timing.path = renderer.Render(lf, camera, options).path;
  std::vector<double> wall_ms, gpu_ms;
  double spent = 0;
  while (int(wall_ms.size()) < policy.max_runs &&
         (int(wall_ms.size()) < policy.min_runs || spent < policy.min_seconds)) {
    const auto start = std::chrono::steady_clock::now();
    const RenderResult result = renderer.Render(lf, camera, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    wall_ms.push_back(seconds * 1e3);
    gpu_ms.push_back(result.gpu_ms);
    spent += seconds;
  }
  timing.runs = int(wall_ms.size());
  timing.wall_median_ms = Median(wall_ms);
  timing.median_ms = renderer.uses_gl() ? Median(gpu_ms) : timing.wall_median_ms;
  return timing;
}

nlohmann::json CellRecord(const BenchCell& cell, const Timing& timing) {
  nlohmann::json r;
  r["table"] = cell.table;
  r["size"] = cell.size;
  r["threads"] = cell.threads > 0 ? cell.threads : tbb::info::default_concurrency();
  r["integrator"] = ToString(cell.integrator);
  r["interpolation"] = ToString(cell.interpolation);
  r["aperture_mm"] = cell.aperture_mm;
  r["lens_rate"] = cell.lens_rate ? nlohmann::json(*cell.lens_rate) : nlohmann::json();
  r["focal_length_mm"] = cell.focal_length_mm;
  r["focus_distance_mm"] = cell.focus_distance_mm;
  r["median_ms"] = timing.median_ms;
  r["wall_median_ms"] = timing.wall_median_ms;
  r["runs"] = timing.runs;
  r["renderer"] = timing.path;
  r["paper_ms"] = cell.paper_ms ? nlohmann::json(*cell.paper_ms) : nlohmann::json();
  if (cell.paper_gpu_ms) r["paper_gpu_ms"] = *cell.paper_gpu_ms;
  return r;
}

}  // namespace lfcam
