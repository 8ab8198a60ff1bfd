// `lfcam info` (what a light field file holds) and `lfcam compare` (PSNR and SSIM).
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lfcam/cli/commands.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/image_metrics.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/lightfield_compare.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/lightfield_video_file.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/view_filling.h"

namespace lfcam::cli {
namespace {

std::string Vec(const Vec3& v) {
  return fmt::format("({:.3f}, {:.3f}, {:.3f})", v.x(), v.y(), v.z());
}

// Each view's camera centre in world millimetres: measured (a built or imported light field)
// or the slab's ideal grid point. Where to put the virtual camera to stand where a camera was.
nlohmann::json CameraCentres(const LightFieldHeader& h) {
  nlohmann::json cameras = nlohmann::json::array();
  for (int r = 0; r < h.dims.rows; ++r)
    for (int c = 0; c < h.dims.cols; ++c) {
      const Vec3 p = h.measured_poses.empty()
                         ? h.slab.uv.camera_center(r, c)
                         : h.measured_poses[std::size_t(r * h.dims.cols + c)].center;
      cameras.push_back({{"row", r}, {"col", c}, {"center_mm", {p.x(), p.y(), p.z()}}});
    }
  return cameras;
}

// Each view's st window (format version 4): null when the views share the st domain, else each
// view's offset from it in samples.
nlohmann::json StWindows(const LightFieldHeader& h) {
  if (h.st_offsets.empty()) return nullptr;
  nlohmann::json views = nlohmann::json::array();
  for (std::size_t i = 0; i < h.st_offsets.size(); ++i)
    views.push_back({{"row", i / std::size_t(h.dims.cols)},
                     {"col", i % std::size_t(h.dims.cols)},
                     {"st_offset", {h.st_offsets[i].k, h.st_offsets[i].l}}});
  return views;
}

nlohmann::json InfoJson(const LightFieldHeader& h) {
  const std::size_t bytes =
      h.dims.samples_per_view() * h.dims.view_count() * 3 * BytesPerChannel(h.sample_type);
  return {{"format_version", h.version},
          {"rows", h.dims.rows},
          {"cols", h.dims.cols},
          {"n_s", h.dims.n_s},
          {"n_t", h.dims.n_t},
          {"channels", LightFieldDims::kChannels},
          {"sample_type", ToString(h.sample_type)},
          {"compression", h.compression == Compression::kNone ? "none" : "zstd"},
          {"sample_bytes", bytes},
          {"stored_bytes", h.stored_sample_bytes},
          {"file_bytes", h.file_bytes},
          {"slab", h.slab},
          {"separation_mm", h.slab.separation_mm()},
          {"metadata", h.metadata},
          {"measured_poses", !h.measured_poses.empty()},
          {"view_cameras", !h.measured_poses.empty() && h.measured_poses.front().intrinsics},
          {"view_windows", StWindows(h)},
          {"cameras", CameraCentres(h)}};
}

}  // namespace

void AddInfoCommand(CLI::App& app) {
  auto* info = app.add_subcommand("info", "Describe a light field file");
  struct Flags {
    std::string input;
    bool json = false, verify = false;
  };
  auto flags = std::make_shared<Flags>();
  info->add_option("lightfield", flags->input, "Light field file (.lf) or video (.lfv)")
      ->required();
  info->add_flag("--json", flags->json, "Machine-readable output (JSON on stdout)");
  info->add_flag("--verify", flags->verify,
                 "Also read every view and check its checksum (exit 1 if any is corrupt)");
  info->callback([flags] {
    const LightFieldVideo video(flags->input);
    if (video.frame_count() == 0)
      throw Error(fmt::format("{}: a light field video with no frame yet{}", flags->input,
                              video.complete() ? "" : " (still being written?)"));
    const LightFieldHeader h = video.FrameHeader(0);
    double verify_ms = -1;
    if (flags->verify) {
      const auto start = std::chrono::steady_clock::now();
      for (std::size_t k = 0; k < video.frame_count(); ++k) (void)video.ReadFrame(k);
      verify_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
    }
    auto j = InfoJson(h);
    nlohmann::json video_json;
    if (video.is_video()) {
      const auto& vh = video.header();
      const double duration = double(video.frame_count()) / vh.fps;
      video_json = {{"frames", video.frame_count()},
                    {"frames_planned", vh.frames_planned},
                    {"complete", video.complete()},
                    {"fps", vh.fps},
                    {"duration_s", duration},
                    {"start_unix_ns", vh.start_unix_ns},
                    {"file_bytes", video.file_bytes()},
                    {"bytes_per_frame", double(video.file_bytes()) / double(video.frame_count())},
                    {"metadata", vh.metadata}};
      j["video"] = video_json;
      j["file_bytes"] = video.file_bytes();
    }
    // Reaching here with --verify means every view was read and its checksum matched: a failed
    // check throws, and the command exits 1 (with {"error": ...} under --json).
    if (flags->verify) {
      j["verified"] = true;
      j["verified_read_ms"] = verify_ms;
    }
    if (flags->json) {
      fmt::print("{}\n", JsonToText(j, 2));
      return;
    }
    const Slab& s = h.slab;
    fmt::print("{}\n", flags->input);
    if (video.is_video()) {
      const auto& vh = video.header();
      fmt::print(
          "  video         {} frames at {:g} fps ({:.2f} s){}; {:.1f} MB, {:.1f} MB a frame\n",
          video.frame_count(), vh.fps, double(video.frame_count()) / vh.fps,
          video.complete() ? ""
                           : fmt::format(" of {} planned: still being written, or its "
                                         "build stopped",
                                         vh.frames_planned),
          double(video.file_bytes()) / 1e6,
          double(video.file_bytes()) / 1e6 / double(video.frame_count()));
      const nlohmann::json& sync = vh.metadata.value("sync_report", nlohmann::json::object());
      if (sync.contains("spread_us")) {
        const auto& sp = sync["spread_us"];
        fmt::print(
            "  sync          {} ({}): spread median {:.1f} us, max {:.1f} us over {} frames\n",
            vh.metadata.value("sync", "?"), vh.metadata.value("recording", "?"),
            sp.value("median", 0.0), sp.value("max", 0.0), sp.value("frames", 0));
        std::int64_t missing = 0;
        for (const auto& c : sync.value("cameras", nlohmann::json::array()))
          missing += c.value("missing", std::int64_t(0));
        fmt::print(
            "                {} camera frames missing (filled from neighbours; each "
            "frame's metadata names them){}\n",
            missing,
            sync.value("problems", nlohmann::json::array()).empty()
                ? ""
                : fmt::format("; {} camera problems (--json)", sync["problems"].size()));
      }
      fmt::print("  frame 0:\n");
    }
    fmt::print("  light field   {} x {} views of {} x {} st samples, RGB {}\n", h.dims.rows,
               h.dims.cols, h.dims.n_s, h.dims.n_t, ToString(h.sample_type));
    fmt::print("  size          {:.1f} MB of samples, {:.1f} MB on disk ({})\n",
               j["sample_bytes"].get<double>() / 1e6, h.file_bytes / 1e6,
               j["compression"].get<std::string>());
    const std::string unit = WorldLengthUnit(h.metadata);
    if (unit != "mm")
      fmt::print(
          "  lengths       in units of the cameras' spacing, not mm (the import knew no scale; "
          "import with --pitch-mm for mm)\n");
    fmt::print("  uv (array)    p_ca {}  rows {}  cols {}  pitch {:.6g} {}\n", Vec(s.uv.p_ca),
               s.uv.rows, s.uv.cols, s.uv.pitch_mm, unit);
    fmt::print("                u_ca {}  v_ca {}  n_ca {}\n", Vec(s.uv.u_ca), Vec(s.uv.v_ca),
               Vec(s.uv.n_ca));
    fmt::print("  st (view window) origin {}  x {}  y {}  {:.6g} x {:.6g} {}\n", Vec(s.st.origin),
               Vec(s.st.x_axis), Vec(s.st.y_axis), s.st.width_mm, s.st.height_mm, unit);
    fmt::print("  st domain     [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]\n", s.st_domain.s0,
               s.st_domain.s1, s.st_domain.t0, s.st_domain.t1);
    if (!h.st_offsets.empty()) {
      int k0 = 0, k1 = 0, l0 = 0, l1 = 0;
      for (const StOffset& o : h.st_offsets)
        k0 = std::min(k0, o.k), k1 = std::max(k1, o.k), l0 = std::min(l0, o.l),
        l1 = std::max(l1, o.l);
      fmt::print(
          "  view windows  each view its own: the st domain's grid moved by {}..{} samples "
          "along s, {}..{} along t\n",
          k0, k1, l0, l1);
    }
    fmt::print("  plane gap     {:.1f} {}\n", s.separation_mm(), unit);
    // Metadata: in full when short; else each top-level field, long values elided.
    const std::string metadata = JsonToText(h.metadata);
    if (metadata.size() <= 160) {
      fmt::print("  metadata      {}\n", metadata);
    } else {
      fmt::print("  metadata      (--json shows all)\n");
      for (const auto& [key, value] : h.metadata.items()) {
        std::string text = JsonToText(value);
        if (text.size() > 100) text = text.substr(0, 96) + " ...";
        fmt::print("    {:<12}  {}\n", key, text);
      }
    }
    if (!h.measured_poses.empty())
      fmt::print("  cameras       {} recorded for all {} views{}\n",
                 h.measured_poses.front().intrinsics ? "the camera that took each view"
                                                     : "measured centres",
                 h.measured_poses.size(),
                 h.measured_poses.front().intrinsics ? " (render --as-camera R,C)" : "");
    if (const auto filled = FilledViews(h.metadata, h.dims.rows, h.dims.cols); !filled.empty()) {
      std::vector<std::string> labels;
      for (const auto& [r, c] : filled) labels.push_back(fmt::format("({}, {})", r, c));
      fmt::print(
          "  filled        {} view{} filled from {} neighbours, no photograph{} (depth, the depth "
          "lookup, click to focus and export leave {} out): {}\n",
          filled.size(), filled.size() == 1 ? "" : "s", filled.size() == 1 ? "its" : "their",
          filled.size() == 1 ? "" : "s", filled.size() == 1 ? "it" : "them",
          fmt::join(labels, ", "));
    }
    if (flags->verify)
      fmt::print("  verified      all views{} read and checked in {:.0f} ms\n",
                 video.is_video() ? " of every frame" : "", verify_ms);
  });
}

namespace {

// Runs f(); an lfcam::Error it throws is prefixed with both file names unless it names one.
template <typename F>
auto WithFiles(const std::string& a, const std::string& b, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.find(a) != std::string::npos || what.find(b) != std::string::npos) throw;
    throw Error(fmt::format("{} and {}: {}", a, b, what));
  }
}

}  // namespace

void AddCompareCommand(CLI::App& app) {
  auto* compare =
      app.add_subcommand("compare", "PSNR and SSIM between two images (or two .lf light fields)");
  struct Flags {
    std::string a, b, mask;
    bool json = false;
  };
  auto flags = std::make_shared<Flags>();
  compare->add_option("a", flags->a, "First image")->required();
  compare->add_option("b", flags->b, "Second image")->required();
  compare->add_option("--mask", flags->mask, "Compare only where this image is nonzero");
  compare->add_flag("--json", flags->json,
                    "Machine-readable output (JSON on stdout; psnr_db is null for identical "
                    "images)");
  compare->callback([flags] {
    auto is_lightfield = [](const std::string& path) {
      return path.size() > 3 && path.compare(path.size() - 3, 3, ".lf") == 0;
    };
    if (is_lightfield(flags->a) && is_lightfield(flags->b)) {
      if (!flags->mask.empty()) throw UsageError("--mask: only for images, not light fields");
      const LightFieldComparison r = WithFiles(flags->a, flags->b, [&] {
        return CompareLightFields(ReadLightField(flags->a), ReadLightField(flags->b));
      });
      const bool identical = std::isinf(r.all.psnr_db);
      if (flags->json) {
        fmt::print("{}\n", JsonToText({{"ssim", r.all.ssim},
                                       {"mean_abs_error", r.all.mean_abs_error},
                                       {"samples", r.all.pixels},
                                       {"identical", identical},
                                       {"psnr_db", identical ? nlohmann::json(nullptr)
                                                             : nlohmann::json(r.all.psnr_db)},
                                       {"worst_view",
                                        {{"row", r.worst_row},
                                         {"col", r.worst_col},
                                         {"psnr_db", std::isinf(r.worst_view_psnr_db)
                                                         ? nlohmann::json(nullptr)
                                                         : nlohmann::json(r.worst_view_psnr_db)}}}},
                                      2));
        return;
      }
      fmt::print(
          "PSNR {:.2f} dB  SSIM {:.4f}  mean |error| {:.2f}/255 over {} samples; worst "
          "view ({}, {}) {:.2f} dB\n",
          r.all.psnr_db, r.all.ssim, r.all.mean_abs_error, r.all.pixels, r.worst_row, r.worst_col,
          r.worst_view_psnr_db);
      return;
    }
    const cv::Mat a = ReadImageSrgb8(flags->a), b = ReadImageSrgb8(flags->b);
    const cv::Mat mask = flags->mask.empty() ? cv::Mat() : ReadMask(flags->mask);
    ImageComparison r;
    try {
      // SSIM's luma and moment images: about a dozen float planes.
      RequireMemory(48.0 * double(a.total()),
                    fmt::format("comparing {}x{} images", a.cols, a.rows));
      r = CompareImages(a, b, mask);
    } catch (const Error& e) {
      throw Error(fmt::format("{} and {}: {}", flags->a, flags->b, e.what()));
    }
    if (flags->json) {
      // JSON has no infinity: identical images have "psnr_db": null and "identical": true.
      const bool identical = std::isinf(r.psnr_db);
      nlohmann::json j = {
          {"ssim", r.ssim},
          {"mean_abs_error", r.mean_abs_error},
          {"pixels", r.pixels},
          {"identical", identical},
          {"psnr_db", identical ? nlohmann::json(nullptr) : nlohmann::json(r.psnr_db)}};
      fmt::print("{}\n", JsonToText(j, 2));
      return;
    }
    fmt::print("PSNR {:.2f} dB  SSIM {:.4f}  mean |error| {:.2f}/255 over {} pixels\n", r.psnr_db,
               r.ssim, r.mean_abs_error, r.pixels);
  });
}

}  // namespace lfcam::cli
