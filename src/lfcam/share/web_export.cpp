#include "lfcam/share/web_export.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <string_view>
#include <vector>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/staged_folder.h"
#include "lfcam/io/lightfield_export.h"
#include "lfcam/share/web/index.html.h"
#include "lfcam/share/web/lfcam-web.js.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

std::string Base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v =
        (std::uint32_t(bytes[i]) << 16) | (std::uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
    out += {kDigits[v >> 18], kDigits[(v >> 12) & 63], kDigits[(v >> 6) & 63], kDigits[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const std::uint32_t v = std::uint32_t(bytes[i]) << 16;
    out += {kDigits[v >> 18], kDigits[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const std::uint32_t v = (std::uint32_t(bytes[i]) << 16) | (std::uint32_t(bytes[i + 1]) << 8);
    out += {kDigits[v >> 18], kDigits[(v >> 12) & 63], kDigits[(v >> 6) & 63], '='};
  }
  return out;
}

nlohmann::json Vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

void WriteText(const fs::path& path, std::string_view text) {
  WriteFileAtomically(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

// The light field's description for the page (lfcam-web.js reads it), without the views.
nlohmann::json PageMetadata(const LightField& lf, const WebExportOptions& options, int n_s, int n_t,
                            int scale) {
  const Slab& slab = lf.slab();
  const ArrayPlane& a = slab.uv;
  const ViewWindow& w = slab.st;
  const auto& d = lf.dims();
  nlohmann::json centers = nlohmann::json::array(), offsets = nlohmann::json::array();
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) {
      centers.push_back(Vec(lf.camera_center(r, c)));
      const StOffset o = lf.st_offset(r, c);
      offsets.push_back({double(o.k) / scale, double(o.l) / scale});
    }
  const StDomain& ref = slab.st_domain;
  const StDomain all = lf.st_union();
  const VirtualCameraParams& cam = options.camera;
  nlohmann::json meta = {{"format", "lfcam-web"},
                         {"version", 1},
                         {"name", options.name},
                         {"grid", {{"rows", d.rows}, {"cols", d.cols}}},
                         {"array",
                          {{"p_ca", Vec(a.p_ca)},
                           {"u_ca", Vec(a.u_ca)},
                           {"v_ca", Vec(a.v_ca)},
                           {"n_ca", Vec(a.n_ca)},
                           {"rows", a.rows},
                           {"cols", a.cols},
                           {"pitch_mm", a.pitch_mm},
                           {"width_mm", a.width_mm()},
                           {"height_mm", a.height_mm()}}},
                         {"window",
                          {{"origin", Vec(w.origin)},
                           {"x_axis", Vec(w.x_axis)},
                           {"y_axis", Vec(w.y_axis)},
                           {"width_mm", w.width_mm},
                           {"height_mm", w.height_mm}}},
                         {"sampling",
                          {{"s0", ref.s0},
                           {"t0", ref.t0},
                           {"s1", ref.s1},
                           {"t1", ref.t1},
                           {"n_s", n_s},
                           {"n_t", n_t}}},
                         {"union", {all.s0, all.t0, all.s1, all.t1}},
                         {"centers", centers},
                         {"view_size", {n_s, n_t}},
                         {"source_size", {d.n_s, d.n_t}},
                         {"camera",
                          {{"width", cam.width},
                           {"height", cam.height},
                           {"focal_length_mm", cam.focal_length_mm},
                           {"focus_distance_mm", cam.focus_distance_mm},
                           {"aperture_mm", cam.aperture_mm},
                           {"breathing", cam.breathing}}}};
  meta["offsets"] = lf.has_view_windows() ? offsets : nlohmann::json(nullptr);
  // What its lengths are ("mm", or "units" of the cameras' spacing): the page's labels say so.
  meta["length_unit"] = WorldLengthUnit(lf.metadata());
  return meta;
}

}  // namespace

WebExportReport ExportWeb(const LightField& lf, const WebExportOptions& options,
                          const fs::path& out_dir) {
  const auto& d = lf.dims();
  static_cast<void>(VirtualCamera(options.camera));  // the first view must make sense
  StagedFolder folder(out_dir);
  const std::uint64_t page_bytes = sizeof(kIndexHtml) - 1 + sizeof(kLfcamWebJs) - 1;
  std::vector<cv::Mat> full;
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) full.push_back(ViewImage(lf, r, c));

  for (int scale = 1;; ++scale) {
    const int n_s = std::max(1, int(std::lround(double(d.n_s) / scale)));
    const int n_t = std::max(1, int(std::lround(double(d.n_t) / scale)));
    if (n_s < 16 || n_t < 16)
      throw Error(fmt::format(
          "the light field does not fit a web page of {:.3g} MB even at {}x{} samples a view",
          options.max_download_bytes / 1e6, n_s, n_t));
    if (std::max(n_s, n_t) > options.max_texture_side ||
        4ull * std::uint64_t(n_s) * n_t * d.view_count() > options.max_texture_bytes)
      continue;
    std::vector<cv::Mat> views = full;
    if (scale > 1)
      for (cv::Mat& view : views) cv::resize(view, view, {n_s, n_t}, 0, 0, cv::INTER_AREA);
    for (const int quality : {options.jpeg_quality, 80, 70}) {
      if (quality > options.jpeg_quality) continue;
      nlohmann::json urls = nlohmann::json::array();
      std::uint64_t bytes = page_bytes;
      for (const cv::Mat& view : views) {
        urls.push_back("data:image/jpeg;base64," + Base64(EncodeJpeg(view, quality)));
        bytes += urls.back().get_ref<const std::string&>().size() + 4;
        if (bytes > options.max_download_bytes) break;
      }
      if (bytes > options.max_download_bytes) continue;
      WebExportReport report;
      report.scale = scale;
      report.view_width = n_s;
      report.view_height = n_t;
      report.jpeg_quality = quality;
      report.note = scale == 1 ? fmt::format("every st sample, JPEG quality {}", quality)
                               : fmt::format(
                                     "1/{} of the st samples each way ({}x{} of {}x{}), "
                                     "JPEG quality {}",
                                     scale, n_s, n_t, d.n_s, d.n_t, quality);
      nlohmann::json meta = PageMetadata(lf, options, n_s, n_t, scale);
      meta["note"] = report.note;
      meta["views"] = std::move(urls);
      const std::string head =
          "// A light field for lfcam's web page (lfcam export --format web).\n"
          "window.LFCAM_LIGHTFIELD = ";
      // The page states its own size: the number's digits change the size, so until it holds.
      std::string data;
      report.download_bytes = 0;
      for (int tries = 0; tries < 4; ++tries) {
        meta["download_bytes"] = report.download_bytes;
        data = head + meta.dump() + ";\n";
        if (page_bytes + data.size() == report.download_bytes) break;
        report.download_bytes = page_bytes + data.size();
      }
      // The views were counted before; the geometry too must fit.
      if (report.download_bytes > options.max_download_bytes) continue;
      WriteText(folder.path() / "lightfield.js", data);
      WriteText(folder.path() / "index.html", kIndexHtml);
      WriteText(folder.path() / "lfcam-web.js", kLfcamWebJs);
      folder.Commit();
      return report;
    }
  }
}

}  // namespace lfcam
