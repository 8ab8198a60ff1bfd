// `lfcam bench table1|table2`: the paper's Tables 1 and 2 on this machine, beside the paper's.
#include <fmt/core.h>
#include <tbb/info.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "lfcam/cli/backend_flags.h"
#include "lfcam/cli/bench_playback.h"
#include "lfcam/cli/bench_video.h"
#include "lfcam/cli/bench_viewer.h"
#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/progress.h"
#include "lfcam/core/signal_cleanup.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/render/benchmark_tables.h"
#include "lfcam/render/simd_kernels.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam::cli {
namespace {

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  return "unknown CPU";
}

// The `paper` scene simulated with `o`, a progress bar labelled `label` drawn meanwhile.
LightField SimulatePaper(SimulateLightFieldOptions o, const std::string& label, bool quiet) {
  ProgressBar progress(label, o.rows * o.cols, ProgressWanted(quiet));
  if (const auto advance = progress.callback()) o.progress = [advance](int, int) { advance(1); };
  LightField lf = SimulateLightField(MakePaperScene(), o);
  progress.finish();
  return lf;
}

// The paper's light field: the `paper` scene seen by a 10 x 10 array, 1248 x 1152 samples a
// view over the st domain [-1.2, 1.2]^2, one ray a sample.
LightField PaperBenchLightField(bool quiet) {
  SimulateLightFieldOptions o;
  o.st_domain = StDomain{-1.2, -1.2, 1.2, 1.2};
  o.supersampling = 1;
  return SimulatePaper(o, "simulating the 10x10x1248x1152 light field", quiet);
}

// The light field a user has (--users-case): the `paper` scene simulated as `lfcam simulate
// lightfield` does by default, over the st domain [0, 1]^2 that `lfcam build` gives a full-size
// capture, with the bench light field's views and samples (the default bench's: samples 2.4 times
// finer each way than its own), written to a file and read back mapped, as `lfcam render FILE`
// reads one. The file is removed once mapped (the mapping stays).
LightField UsersCaseLightField(const LightFieldDims& dims, bool quiet) {
  SimulateLightFieldOptions o;
  o.rows = dims.rows;
  o.cols = dims.cols;
  o.n_s = dims.n_s;
  o.n_t = dims.n_t;
  const LightField simulated =
      SimulatePaper(o,
                    fmt::format("simulating the user's {}x{}x{}x{} light field", dims.rows,
                                dims.cols, dims.n_s, dims.n_t),
                    quiet);
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     fmt::format("lfcam-bench-users-case-{}.lf", ::getpid());
  const TemporaryFileRegistration registration(path);
  WriteLightField(simulated, path);
  try {
    LightField mapped = ReadLightField(path);
    std::filesystem::remove(path);
    return mapped;
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    throw;
  }
}

std::string Ms(double ms) {
  return ms < 10 ? fmt::format("{:.2f}", ms) : fmt::format("{:.1f}", ms);
}

}  // namespace

void AddBenchCommand(CLI::App& app) {
  auto* bench = app.add_subcommand(
      "bench", "Time the renderer on the paper's Tables 1 and 2, beside the paper's figures");
  struct Flags {
    std::string table, lightfield, json, depth, integrator = "lens-samples",
                                                interpolation = "quadrilinear";
    BackendFlags backend;
    int min_runs = 5;
    double min_seconds = 1.0;
    bool reference = false, quiet = false, users_case = false;
    double aperture_mm = 0;
    std::string size = "1920x1080";
  };
  auto flags = std::make_shared<Flags>();
  bench
      ->add_option("table", flags->table,
                   "table1 (pinhole, 768^2 to 2048^2, one thread and all cores), table2 "
                   "(1024^2, f 444, d_o 4000, d_l 64..256 x gamma 1..16) or video (`render "
                   "--video`: Fig. 11 (a)'s 60-frame 1024^2 refocus sweep, rendered alone and "
                   "encoded to H.264 alongside) or playback (the viewer playing the "
                   "--lightfield VIDEO.lfv without a window: frames kept a second) or viewer (the "
                   "viewer's frames of a still light field without a window, the eye moving: "
                   "wall-clock and GPU time a frame, frames a second)")
      ->required()
      ->check(CLI::IsMember({"table1", "table2", "video", "playback", "viewer"}));
  bench->add_option("--lightfield", flags->lightfield,
                    "Light field to time on (default: simulate the paper's, 10x10 views of "
                    "1248x1152 samples over [-1.2, 1.2]^2, in memory: about 12 s on 2 cores)");
  bench->add_option("--json", flags->json, "Also write one record per cell to this JSON file");
  auto* aperture_option =
      bench
          ->add_option(
              "--aperture", flags->aperture_mm,
              "playback and viewer: the viewer's aperture d_l in mm (playback's default 0: a "
              "pinhole, its first view; viewer's 256)")
          ->check(CLI::Range(0.0, 10000.0));
  bench
      ->add_option("--size", flags->size,
                   "viewer: the window's size, WxH (the frames rendered at full resolution)")
      ->capture_default_str();
  bench->add_flag("--users-case", flags->users_case,
                  "Also time every cell on the light field a user has: the same views and samples "
                  "over `lfcam simulate lightfield`'s default st domain [0, 1]^2 (what `lfcam "
                  "build` gives a capture; the default bench's is 2.4 times finer each way), "
                  "read from a file; printed beside, with the ratio");
  auto* integrator_option =
      bench
          ->add_option("--integrator", flags->integrator,
                       "table2: lens-samples (the paper's), cameras (their limit with the "
                       "focal-plane lookup) or cameras-quadrilinear (the limit of the paper's own "
                       "estimator); for the limits gamma plays no part, so one cell per aperture")
          ->capture_default_str();
  bench
      ->add_option("--interpolation", flags->interpolation,
                   "table2 with lens-samples: quadrilinear (the paper's), focal-plane or depth "
                   "(with --depth)")
      ->capture_default_str();
  bench->add_option("--depth", flags->depth,
                    "With --interpolation depth: the views' depth maps (a folder from `lfcam depth "
                    "--all` or `lfcam simulate lightfield --depth-out`) of the --lightfield");
  bench->add_flag("--reference", flags->reference,
                  "cpu: time the scalar reference renderer instead");
  flags->backend.AddTo(*bench);
  bench
      ->add_option("--min-runs", flags->min_runs, "Timed runs per cell, at least (after a warm-up)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  bench
      ->add_option("--min-seconds", flags->min_seconds,
                   "Keep timing a cell until this many seconds are spent (at most 50 runs)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 600.0));
  bench->add_flag("--quiet", flags->quiet, "No progress bar (it is drawn only on a terminal)");
  bench->callback([flags, integrator_option, aperture_option] {
    const Integrator integrator =
        FlagValue("--integrator", [&] { return IntegratorFromString(flags->integrator); });
    const Interpolation interpolation =
        FlagValue("--interpolation", [&] { return InterpolationFromString(flags->interpolation); });
    if (flags->table == "table1" &&
        (integrator != Integrator::kLensSamples || interpolation != Interpolation::kQuadrilinear))
      throw UsageError(
          "--integrator/--interpolation: table1 is the paper's pinhole with its quadrilinear "
          "lookup; they apply to table2");
    const bool depth_lookup = interpolation == Interpolation::kDepth;
    if (depth_lookup && integrator != Integrator::kLensSamples)
      throw UsageError("--interpolation depth goes with --integrator lens-samples");
    if (depth_lookup && (flags->depth.empty() || flags->lightfield.empty()))
      throw UsageError(
          "--interpolation depth needs --depth DIR, the depth maps of the --lightfield FILE "
          "(`lfcam depth FILE --all --out DIR`, or `lfcam simulate lightfield --depth-out DIR`)");
    if (!flags->depth.empty() && !depth_lookup)
      throw UsageError("--depth: only with --interpolation depth");
    FrameRenderOptions render_options;
    render_options.reference = flags->reference;
    const Backend backend = flags->backend.Validate(render_options);
    if (!flags->json.empty()) RequireWritableOutput(flags->json, "--json");
    const std::unique_ptr<FrameRenderer> opened = BackendFlags::Open(backend);
    // The viewer's and the playback's frames keep the filtered views as the viewer does; the
    // tables time whole frames.
    if (flags->table == "viewer" || flags->table == "playback") opened->KeepPrefilteredViews();
    const FrameRenderer& renderer = *opened;

    // The viewer's default unless --integrator says: the quadrilinear limit.
    const Integrator viewers_integrator =
        integrator_option->count() > 0 ? integrator : Integrator::kCamerasQuadrilinear;
    if (flags->table == "playback") {
      if (flags->lightfield.empty())
        throw UsageError("playback: --lightfield VIDEO.lfv (a light field video) is required");
      PlaybackBenchOptions playback;
      playback.video = flags->lightfield;
      playback.seconds = std::max(5.0, flags->min_seconds);
      playback.aperture_mm = flags->aperture_mm;
      playback.integrator = viewers_integrator;
      BenchPlayback(playback, renderer, render_options);
      return;
    }
    const LightField lf = flags->lightfield.empty() ? PaperBenchLightField(flags->quiet)
                                                    : ReadLightField(flags->lightfield);
    if (flags->table == "viewer") {
      if (flags->users_case || depth_lookup || !flags->json.empty())
        throw UsageError("--users-case, --interpolation depth and --json: not with viewer");
      ViewerBenchOptions viewer;
      std::tie(viewer.width, viewer.height) = ParseSize("--size", flags->size, 16384);
      if (aperture_option->count() > 0) viewer.aperture_mm = flags->aperture_mm;
      viewer.integrator = viewers_integrator;
      viewer.min_frames = flags->min_runs;
      viewer.min_seconds = flags->min_seconds;
      BenchViewer(lf, viewer, renderer, render_options);
      return;
    }
    if (flags->table == "video") {
      if (flags->users_case || depth_lookup || !flags->json.empty())
        throw UsageError("--users-case, --interpolation depth and --json: not with video");
      // The demo's integrator unless told otherwise.
      BenchVideo(lf, renderer,
                 integrator_option->count() > 0 ? integrator : Integrator::kCamerasQuadrilinear,
                 interpolation, flags->min_runs, flags->quiet);
      return;
    }
    DepthSet depth;
    if (depth_lookup) {
      depth = ReadDepthSet(flags->depth, lf, DepthsForRendering());
      render_options.depth = &depth;
      if (flags->users_case)
        throw UsageError(
            "--users-case: the user's light field has no depth maps to go with "
            "--interpolation depth");
    }
    std::optional<LightField> users;
    if (flags->users_case) users.emplace(UsersCaseLightField(lf.dims(), flags->quiet));
    const int cores = tbb::info::default_concurrency();
    const std::string cpu = CpuModel();
    fmt::print("machine: {}, {} cores, {} vectors; light field {}x{} views of {}x{} samples\n", cpu,
               cores, KernelTargetName(), lf.dims().rows, lf.dims().cols, lf.dims().n_s,
               lf.dims().n_t);
    fmt::print("renderer: {}{}\n", renderer.description(),
               renderer.uses_gl()
                   ? fmt::format(", work group {}x{}; ms: {}", render_options.workgroup_x,
                                 render_options.workgroup_y,
                                 renderer.gl()->device().software
                                     ? "the compute pass to glFinish, wall-clock (a software "
                                       "GL's timer queries miss compute work)"
                                     : "the GPU's, from timer queries")
                   : std::string());
    std::vector<BenchCell> cells =
        flags->table == "table1" ? Table1Cells() : Table2Cells(integrator, interpolation);
    // On the GPU the CPU's thread count plays no part: one cell per size.
    if (renderer.uses_gl()) std::erase_if(cells, [](const BenchCell& c) { return c.threads == 1; });
    const TimingPolicy policy{flags->min_runs, std::max(50, flags->min_runs), flags->min_seconds};
    nlohmann::json records = nlohmann::json::array();
    // The user's case: its time, and how much longer than on the bench's light field.
    const std::string users_header =
        users ? fmt::format(" | {:>10} {:>7}", "user's ms", "longer") : "";
    if (flags->table == "table1")
      fmt::print("{:>6} {:>8} {:>10} {:>5} | {:>12} {:>8} | {:>9} {:>8}{}\n", "image", "threads",
                 "ms", "runs", "paper CPU 1t", "ratio", "paper GPU", "ratio", users_header);
    else
      fmt::print("{:>5} {:>6} {:>14} {:>10} {:>5} | {:>9} {:>8}{}\n", "d_l", "gamma", "integrator",
                 "ms", "runs", "paper GPU", "ratio", users_header);
    for (BenchCell cell : cells) {
      const Timing t = TimeCell(lf, cell, renderer, render_options, policy);
      std::optional<Timing> user;
      if (users) user = TimeCell(*users, cell, renderer, render_options, policy);
      const std::string users_cells = user ? fmt::format(" | {:>10} {:>6.2f}x", Ms(user->median_ms),
                                                         user->median_ms / t.median_ms)
                                           : "";
      if (cell.threads == 0) cell.threads = cores;
      const std::string threads = renderer.uses_gl() ? "gpu" : fmt::format("{}", cell.threads);
      // ratio: the paper's time over ours (above 1: faster than the paper).
      const double ratio = cell.paper_ms ? *cell.paper_ms / t.median_ms : 0;
      if (cell.table == "table1")
        fmt::print("{:>6} {:>8} {:>10} {:>5} | {:>12} {:>7.1f}x | {:>9} {:>7.2f}x{}\n",
                   fmt::format("{}^2", cell.size), threads, Ms(t.median_ms), t.runs,
                   Ms(*cell.paper_ms), ratio, Ms(*cell.paper_gpu_ms),
                   *cell.paper_gpu_ms / t.median_ms, users_cells);
      else
        fmt::print("{:>5} {:>6} {:>14} {:>10} {:>5} | {:>9} {:>7.2f}x{}\n", cell.aperture_mm,
                   cell.lens_rate ? fmt::format("{}", *cell.lens_rate) : std::string("-"),
                   ToString(cell.integrator), Ms(t.median_ms), t.runs, Ms(*cell.paper_ms), ratio,
                   users_cells);
      std::fflush(stdout);
      nlohmann::json record = CellRecord(cell, t);
      if (user) {
        record["users_case_ms"] = user->median_ms;
        record["users_case_runs"] = user->runs;
      }
      if (renderer.uses_gl()) record["threads"] = nullptr;
      record["backend"] = renderer.uses_gl() ? "gl" : "cpu";
      records.push_back(std::move(record));
    }
    fmt::print("ratio: the paper's time over this machine's (above 1: faster than the paper)\n");
    if (users)
      fmt::print(
          "user's ms: the same cell on the user's light field (st domain [0, 1]^2, from a file); "
          "longer: its time over the bench light field's\n");
    if (!flags->json.empty()) {
      nlohmann::json doc;
      doc["machine"] = {{"cpu", cpu}, {"cores", cores}, {"vectors", KernelTargetName()}};
      doc["light_field"] = flags->lightfield.empty() ? "simulated paper scene" : flags->lightfield;
      if (users)
        doc["users_case"] =
            "the paper scene simulated over the st domain [0, 1]^2 with the same views and "
            "samples, "
            "read from a file";
      doc["renderer"] = flags->reference ? "reference" : "fast";
      doc["backend"] = renderer.uses_gl() ? "gl" : "cpu";
      if (const GlRenderer* gl = renderer.gl())
        doc["gpu"] = {{"renderer", gl->device().renderer},
                      {"vendor", gl->device().vendor},
                      {"version", gl->device().version},
                      {"workgroup", flags->backend.workgroup}};
      doc["cells"] = std::move(records);
      const std::string text = doc.dump(2) + "\n";
      WriteFileAtomically(flags->json,
                          {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
      fmt::print("wrote {}\n", flags->json);
    }
  });
}

}  // namespace lfcam::cli
