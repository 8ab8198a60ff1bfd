// `lfcam depth FILE --out depth.png [--view R,C | --all] [--depth-range NEAR,FAR] [--reach N]
// [--backend cpu|gl|auto] [--json]`: depth from the light field itself (depth/plane_sweep.h;
// docs/depth.md), its cost volumes on the GPU with --backend gl (depth/gl_cost_volume.h).
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/lightfield_video_file.h"
#include "lfcam/core/progress.h"
#include "lfcam/depth/cost_volume.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/depth/disparity_map.h"
#include "lfcam/depth/gl_cost_volume.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/render/frame_renderer.h"

namespace lfcam::cli {
namespace {

// What a map holds, for people and --json.
nlohmann::json Summary(const DepthMap& map) {
  double sum = 0, confident = 0, lo = INFINITY, hi = -INFINITY;
  const int n = map.n_s() * map.n_t();
  for (int l = 0; l < map.n_t(); ++l)
    for (int k = 0; k < map.n_s(); ++k) {
      const float d = map.depth.at<float>(l, k);
      if (!std::isfinite(d)) continue;
      lo = std::min(lo, double(d));
      hi = std::max(hi, double(d));
      sum += d;
      confident += !map.confidence.empty() && map.confidence.at<float>(l, k) >= 0.25f;
    }
  return {{"view", {map.row, map.col}},
          {"n_s", map.n_s()},
          {"n_t", map.n_t()},
          {"range_mm", {map.range.near_mm, map.range.far_mm}},
          {"min_mm", std::isfinite(lo) ? lo : 0.0},
          {"max_mm", std::isfinite(hi) ? hi : 0.0},
          {"mean_mm", n > 0 ? sum / n : 0.0},
          {"confident_share", n > 0 ? confident / n : 0.0},
          {"noise_levels", map.noise_levels},
          {"near_nyquist_share", map.near_nyquist_share},
          {"read_sigma", map.read_sigma},
          {"camera_blur_sigma", map.camera_blur_sigma},
          {"views_too_dark", map.views_too_dark},
          {"reach", map.reach}};
}

// Says which views a map left out as too dark to match its reference.
void PrintViewsTooDark(const DepthMap& map) {
  if (map.views_too_dark.empty()) return;
  std::vector<std::string> views;
  for (const auto& [r, c] : map.views_too_dark) views.push_back(fmt::format("{},{}", r, c));
  fmt::print(
      "  left out {} view{} darker than 1/{:g} of the reference view's brightness, too dark to "
      "match (black, or vignetted nearly so): {} (docs/depth.md, \"Views too dark to match\")\n",
      views.size(), views.size() == 1 ? "" : "s", kMaxBrightnessGain, fmt::join(views, " "));
}

// Says how noisy or sharp views were read, when they were read through a Gaussian.
void PrintGaussianReads(const nlohmann::json& summary) {
  if (const double sigma = summary["camera_blur_sigma"].get<double>(); sigma > 0)
    fmt::print(
        "  the views are sampled {:.1f} times as finely as their cameras' pixels: matched after a "
        "Gaussian of {:.1f} samples (half a camera pixel; docs/depth.md, \"Views finer than their "
        "cameras\")\n",
        sigma / kCameraBlurPixels, sigma);
  if (summary["read_sigma"].get<double>() <= 0) return;
  const double noise = summary["noise_levels"].get<double>();
  if (noise > kNoisyViewLevels)
    fmt::print(
        "  the views are noisy (about {:.1f} levels in 8 bits): matched through a Gaussian of "
        "{:.1f} samples rather than Keys' cubic (docs/depth.md, \"Noisy views\")\n",
        noise, summary["read_sigma"].get<double>());
  else
    fmt::print(
        "  the views are sharper than their sampling ({:.1f}% of their texture's power near it): "
        "matched through a Gaussian of {:.1f} samples rather than Keys' cubic (docs/depth.md, "
        "\"Sharp views\")\n",
        100.0 * summary["near_nyquist_share"].get<double>(), summary["read_sigma"].get<double>());
}

// The GPU engine --backend asks for, or none (the CPU): gl must find a GL 4.3 context; auto
// takes a hardware GPU when there is one and says which it took.
std::unique_ptr<GlCostVolume> OpenEngine(const std::string& flag, bool quiet) {
  const Backend backend = FlagValue("--backend", [&] { return BackendFromString(flag); });
  if (backend == Backend::kCpu) return nullptr;
  std::unique_ptr<GlCostVolume> engine;
  try {
    engine = GlCostVolume::Create();
  } catch (const Error& e) {
    if (backend == Backend::kGl) throw Error(std::string("--backend gl: ") + e.what());
    if (!quiet) fmt::print("depth: no GPU ({}): the cost volumes on the CPU\n", e.what());
    return nullptr;
  }
  if (backend == Backend::kAuto && engine->device().software) {
    if (!quiet)
      fmt::print("depth: no hardware GPU (only {}): the cost volumes on the CPU\n",
                 engine->device().renderer);
    return nullptr;
  }
  return engine;
}

// What the GPU engine did, for people and --json.
nlohmann::json EngineReport(const GlCostVolume& engine) {
  const GlCostVolume::Tally t = engine.tally();
  return {{"device", engine.device().renderer}, {"gpu_sweeps", t.gpu_sweeps},
          {"gpu_seconds", t.gpu_seconds},       {"gpu_upload_seconds", t.upload_seconds},
          {"gpu_pass_seconds", t.pass_seconds}, {"gpu_readback_seconds", t.readback_seconds},
          {"cpu_sweeps", t.cpu_sweeps},         {"cpu_reasons", t.cpu_reasons}};
}

void PrintEngineReport(const nlohmann::json& r) {
  fmt::print(
      "cost volumes: {} swept on {} in {:.2f} s (uploading {:.2f} s, the passes {:.2f} s, reading "
      "back {:.2f} s)",
      r["gpu_sweeps"].get<int>(), r["device"].get<std::string>(), r["gpu_seconds"].get<double>(),
      r["gpu_upload_seconds"].get<double>(), r["gpu_pass_seconds"].get<double>(),
      r["gpu_readback_seconds"].get<double>());
  if (r["cpu_sweeps"].get<int>() > 0)
    fmt::print("; {} on the CPU: {}", r["cpu_sweeps"].get<int>(),
               fmt::join(r["cpu_reasons"].get<std::vector<std::string>>(), "; "));
  fmt::print("\n");
}

}  // namespace

void AddDepthCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "depth", "Estimate depth maps from the light field itself (plane sweep), with confidence");
  struct Flags {
    int frame = 0;
    std::string input, out, view, range, disparity_pfm, backend = "cpu";
    bool all = false, json = false, quiet = false;
    int reach = 0;
  };
  auto f = std::make_shared<Flags>();
  command->add_option("lightfield", f->input, "Light field file (.lf) or video (.lfv)")->required();
  command->add_option("--frame", f->frame, "A video's light field frame (from 0)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1 << 30));
  command
      ->add_option("--out", f->out,
                   "Depth PNG to write (16-bit; with NAME.confidence.png and NAME.preview.png "
                   "beside it); with --all, the folder for every view's map")
      ->required();
  command->add_option("--view", f->view, "The view R,C (default: the central one)");
  command->add_flag("--all", f->all,
                    "Every view, one depth range for all: the folder that `lfcam render "
                    "--interpolation depth --depth DIR` reads");
  command->add_option("--depth-range", f->range,
                      "NEAR,FAR in mm from the array's plane (default: found by a coarse sweep)");
  command
      ->add_option("--reach", f->reach,
                   "Views compared: those up to N grid steps away in rows and columns (default: "
                   "4 for one view; with --all 1, or 2 where neighbouring views see the scene at "
                   "most 8 samples apart: a plenoptic camera, a dense grid)")
      ->check(CLI::Range(1, 64));
  command->add_option(
      "--disparity-pfm", f->disparity_pfm,
      "Also write the view's disparity as the light field depth benchmarks count it (the HCI "
      "benchmark's PFM: st samples, a rectified rig's pixels, between neighbouring views, "
      "positive nearer than the st-plane; docs/depth.md)");
  command
      ->add_option("--backend", f->backend,
                   "Where the cost volumes are computed: cpu, gl (OpenGL compute shaders, "
                   "headless through EGL, on a GPU or Mesa's llvmpipe; the rest of the estimate "
                   "stays on the CPU) or auto (gl on a hardware GPU, else cpu; says which)")
      ->capture_default_str();
  command->add_flag("--json", f->json, "Print what was estimated as JSON");
  command->add_flag("--quiet", f->quiet, "No progress bar (it is drawn only on a terminal)");
  command->callback([f] {
    if (f->all && !f->view.empty()) throw UsageError("--view and --all: give one of them");
    PlaneSweepOptions options;
    options.reach = f->reach;
    if (!f->range.empty()) {
      const auto v = ParseNumbers("--depth-range", f->range, 2);
      options.range = DepthRange{v[0], v[1]};
      if (!options.range->valid())
        throw UsageError(fmt::format("--depth-range {}: needs 0 < NEAR < FAR (mm)", f->range));
    }
    if (f->all && !f->disparity_pfm.empty())
      throw UsageError("--disparity-pfm is one view's: not with --all");
    if (!f->disparity_pfm.empty()) {
      if (std::filesystem::path(f->disparity_pfm).extension() != ".pfm")
        throw UsageError(fmt::format("--disparity-pfm {}: a .pfm file", f->disparity_pfm));
      RequireWritableOutput(f->disparity_pfm, "--disparity-pfm");
    }
    if (f->all) {
      RequireNewOrEmptyFolder("--out", f->out);
    } else {
      if (std::filesystem::path(f->out).extension() != ".png")
        throw UsageError(fmt::format("--out {}: a depth map is a .png", f->out));
      RequireWritableOutput(f->out, "--out");
    }
    const std::unique_ptr<GlCostVolume> engine = OpenEngine(f->backend, f->quiet || f->json);
    options.engine = engine.get();
    const LightField lf = ReadLightFieldFrame(f->input, std::size_t(f->frame));
    const auto& d = lf.dims();
    if (d.view_count() < 2)
      throw Error(fmt::format("{}: depth needs at least two views; it has {}x{}", f->input, d.rows,
                              d.cols));
    int row = (d.rows - 1) / 2, col = (d.cols - 1) / 2;
    if (!f->view.empty()) {
      const auto v = ParseNumbers("--view", f->view, 2);
      if (v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]) || v[0] < 0 || v[1] < 0 ||
          v[0] >= d.rows || v[1] >= d.cols)
        throw UsageError(
            fmt::format("--view {}: not a view of the {}x{} grid (rows and columns "
                        "count from 0)",
                        f->view, d.rows, d.cols));
      row = int(v[0]);
      col = int(v[1]);
    }
    const auto start = std::chrono::steady_clock::now();
    const auto seconds = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    nlohmann::json report = {{"lightfield", f->input}, {"out", f->out}};
    if (f->all) {
      DepthSet set(d);
      ProgressBar progress("depth of every view", std::int64_t(d.view_count()),
                           ProgressWanted(f->quiet));
      const auto advance = progress.callback();
      EstimateDepthSet(
          lf, set, [](int, int) { return true; }, options,
          [&](int, int) {
            if (advance) advance(1);
          });
      progress.finish();
      WriteDepthSet(f->out, set, std::filesystem::path(f->input).filename().string(),
                    WorldLengthUnit(lf.metadata()));
      report["views"] = set.count();
      report["range_mm"] = {set.range().near_mm, set.range().far_mm};
      report["central"] = Summary(set.at((d.rows - 1) / 2, (d.cols - 1) / 2));
      report["seconds"] = seconds();
      if (engine) report["gpu"] = EngineReport(*engine);
      if (f->json) {
        fmt::print("{}\n", JsonToText(report, 2));
        return;
      }
      if (engine) PrintEngineReport(report["gpu"]);
      fmt::print("wrote {} depth maps to {} (range {:.0f} .. {:.0f} {}) in {:.1f} s\n", set.count(),
                 f->out, set.range().near_mm, set.range().far_mm, WorldLengthUnit(lf.metadata()),
                 seconds());
      PrintGaussianReads(report["central"]);
      const int reach = set.at((d.rows - 1) / 2, (d.cols - 1) / 2).reach;
      if (f->reach == 0 && reach > 1)
        fmt::print(
            "  each view compared with the views up to {} steps away: neighbouring views see the "
            "scene at most 8 samples apart, too little to tell its depths apart alone (--reach 1 "
            "is quicker; docs/depth.md, \"The set's reach at narrow baselines\")\n",
            reach);
      int darkened = 0;
      for (int r = 0; r < d.rows; ++r)
        for (int c = 0; c < d.cols; ++c) darkened += !set.at(r, c).views_too_dark.empty();
      if (darkened > 0)
        fmt::print(
            "  {} of the {} maps left out neighbouring views darker than 1/{:g} of their "
            "reference's brightness, too dark to match (docs/depth.md, \"Views too dark to "
            "match\")\n",
            darkened, set.count(), kMaxBrightnessGain);
      return;
    }
    const DepthMap map = EstimateDepth(lf, row, col, options);
    WriteDepthFiles(
        f->out, map,
        JsonToText({{"lightfield", std::filesystem::path(f->input).filename().string()}}),
        WorldLengthUnit(lf.metadata()));
    report["map"] = Summary(map);
    if (!f->disparity_pfm.empty()) {
      const int unknown = WriteDisparityPfm(f->disparity_pfm, DisparityOf(lf, map));
      report["disparity_pfm"] = f->disparity_pfm;
      report["disparity_unknown"] = unknown;
    }
    report["confidence"] = ConfidencePathFor(f->out).string();
    report["preview"] = PreviewPathFor(f->out).string();
    report["seconds"] = seconds();
    if (engine) report["gpu"] = EngineReport(*engine);
    if (f->json) {
      fmt::print("{}\n", JsonToText(report, 2));
      return;
    }
    if (engine) PrintEngineReport(report["gpu"]);
    const nlohmann::json& s = report["map"];
    fmt::print(
        "wrote {} (view {},{}: {}x{}, {:.0f} .. {:.0f} {}, {:.0f}% confident), {} and {} in "
        "{:.1f} s\n",
        f->out, row, col, map.n_s(), map.n_t(), s["min_mm"].get<double>(),
        s["max_mm"].get<double>(), WorldLengthUnit(lf.metadata()),
        100.0 * s["confident_share"].get<double>(), report["confidence"].get<std::string>(),
        report["preview"].get<std::string>(), seconds());
    PrintGaussianReads(s);
    PrintViewsTooDark(map);
    if (!f->disparity_pfm.empty())
      fmt::print(
          "wrote {} (disparity between neighbouring views, st samples; {} unknown written "
          "as 0)\n",
          f->disparity_pfm, report["disparity_unknown"].get<int>());
  });
}

}  // namespace lfcam::cli
