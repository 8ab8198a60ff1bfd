#pragma once
// The paper's Tables 1 and 2 (its §7) as benchmark cells: the cells, the paper's figures, and a
// timer that takes the median of enough runs after a warm-up. `lfcam bench` prints and writes
// them (docs/benchmarks.md).
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/frame_renderer.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

struct BenchCell {
  std::string table;  // "table1" or "table2"
  int size = 1024;    // square image side
  int threads = 0;    // 0: all cores
  Integrator integrator = Integrator::kLensSamples;
  Interpolation interpolation = Interpolation::kQuadrilinear;
  double aperture_mm = 0;
  std::optional<double> lens_rate;  // none for pinholes and the cameras integrator
  double focal_length_mm = 500, focus_distance_mm = 4000;
  std::optional<double> paper_ms;      // the paper's figure (Table 1: its one-thread CPU)
  std::optional<double> paper_gpu_ms;  // Table 1: the paper's fastest GPU work group
};

// Table 1: pinhole, the paper's quadrilinear lookup, 768^2 .. 2048^2, one thread and all
// cores. Table 2: 1024^2, f 444, d_o 4000, d_l 64..256 x gamma 1..16 with lens samples; with
// the cameras integrator gamma plays no part, so one cell per d_l (compared with the paper's
// gamma 16, the closest it came to the limit).
std::vector<BenchCell> Table1Cells();
std::vector<BenchCell> Table2Cells(Integrator integrator, Interpolation interpolation);

// The virtual camera of a cell: at the array's centre, looking along -n_ca (as the paper's
// tables were measured).
VirtualCameraParams CellCamera(const BenchCell& cell, const ArrayPlane& array);

struct Timing {
  double median_ms = 0;       // CPU: wall-clock; GL: the compute pass (GL timer queries)
  double wall_median_ms = 0;  // wall-clock, with the GL frame's set-up and read-back
  int runs = 0;
  std::string path;  // RenderResult::path
};
struct TimingPolicy {
  int min_runs = 5, max_runs = 50;
  double min_seconds = 1.0;  // keep running (up to max_runs) until this much time is spent
};
// One warm-up render, then runs until the policy is met; the median. `options` gives the
// backend's settings (reference, work group); the cell gives the rest.
// The median of timed runs (the mean of the middle two of an even count; 0 for none).
double Median(std::vector<double> values);

Timing TimeCell(const LightField& lf, const BenchCell& cell, const FrameRenderer& renderer,
                FrameRenderOptions options, const TimingPolicy& policy);

// {"table", "size", "threads", "integrator", "aperture_mm", "lens_rate", "median_ms",
//  "paper_ms", ...}: one record.
nlohmann::json CellRecord(const BenchCell& cell, const Timing& timing);

}  // namespace lfcam
