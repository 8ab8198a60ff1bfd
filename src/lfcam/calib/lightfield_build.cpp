#include "lfcam/calib/lightfield_build.h"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <span>
#include <vector>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_header.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/jpeg_region.h"
#include "lfcam/core/least_squares.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/view_filling.h"

namespace lfcam {
namespace {

constexpr int kStatsStride = 8;  // the colour statistics look at every 8th st sample each way

// What one view contributes to the colour statistics, on the coarse st grid.
struct ViewStats {
  std::vector<std::uint8_t> valid;
  std::vector<Vec3> after, before;  // linear, with and without the photometric correction
};

struct ViewJob {
  int row, col;
  const CalibratedCamera* camera;
  const CameraImage* image;
};

// The part of the image a map reads, decoded: R, G, B (CV_8UC3) and where it lies in the image
// scaled by 1/reduction. JPEGs decode only those rows and columns.
struct DecodedRegion {
  cv::Mat rgb;
  cv::Rect roi;
};

DecodedRegion DecodeRegion(std::span<const std::uint8_t> bytes, const std::string& name,
                           int reduction, cv::Size scaled, cv::Rect wanted,
                           ChromaUpsampling chroma) {
  DecodedRegion out;
  if (wanted.area() == 0) return out;
  if (LooksLikeJpeg(bytes)) {
    JpegRegion region = DecodeJpegRegion(bytes, name, reduction, wanted, chroma);
    if (region.scaled != scaled)
      throw Error(fmt::format("{}: decoded at 1/{} size to {}x{}, expected {}x{}", name, reduction,
                              region.scaled.width, region.scaled.height, scaled.width,
                              scaled.height));
    out.rgb = region.rgb;
    out.roi = cv::Rect(region.origin, out.rgb.size());
    return out;
  }
  const cv::Mat bgr = DecodeImageBytes(bytes, name, ImageDecodeMode::kColour8, reduction);
  if (bgr.type() != CV_8UC3 || std::abs(bgr.cols - scaled.width) > 1 ||
      std::abs(bgr.rows - scaled.height) > 1)
    throw Error(fmt::format("{}: not an 8-bit colour image of {}x{} at 1/{} size", name,
                            scaled.width, scaled.height, reduction));
  out.roi = wanted & cv::Rect(0, 0, bgr.cols, bgr.rows);
  cv::cvtColor(bgr(out.roi), out.rgb, cv::COLOR_BGR2RGB);
  return out;
}

// Resamples one camera's image into its view. Returns the decode reduction used.
// Where each st sample of a view falls in its camera's image: the map (in the pixels of the image
// decoded at 1/reduction), its footprint and the part of the image it reads. It depends on the
// camera and the sampling only, so a video makes it once per camera.
ViewMap MakeViewMap(const CalibratedCamera& camera, const StSampling& sampling,
                    const BuildOptions& options) {
  const int n_s = options.n_s, n_t = options.n_t;
  const ViewWindow& st = sampling.window;
  const CameraIntrinsics& k = camera.intrinsics;
  const Rigid3 camera_from_world = camera.world_from_camera.inverse();
  const Mat3& r = camera_from_world.rotation;
  // Camera-frame point of st position (s, t): s * a_s + t * a_t + a_0.
  const Vec3 a_s = r * (st.width_mm * st.x_axis);
  const Vec3 a_t = r * (st.height_mm * st.y_axis);
  const Vec3 a_0 = camera_from_world * st.origin;
  auto pixel_of = [&](double kk, double ll) -> Vec2 {
    const double s = sampling.s_of(kk), t = sampling.t_of(ll);
    const Vec3 q = s * a_s + t * a_t + a_0;
    if (!(q.z() > 1e-9)) return Vec2(-1e9, -1e9);  // behind the camera
    const Vec2 n = k.distortion.Apply(Vec2(q.x() / q.z(), q.y() / q.z()));
    return Vec2(k.fx * n.x() + k.cx, k.fy * n.y() + k.cy);
  };
  ViewMap m;
  // The map's footprint at the view's centre, in full-resolution pixels per st sample.
  const Vec2 c = pixel_of(0.5 * n_s, 0.5 * n_t);
  m.footprint = std::max((pixel_of(0.5 * n_s + 1, 0.5 * n_t) - c).norm(),
                         (pixel_of(0.5 * n_s, 0.5 * n_t + 1) - c).norm());
  while (m.reduction < 8 && 2.0 * m.reduction <= m.footprint) m.reduction *= 2;
  const int reduction = m.reduction;
  m.scaled =
      cv::Size((k.width + reduction - 1) / reduction, (k.height + reduction - 1) / reduction);
  const cv::Size scaled = m.scaled;

  // The map, in the scaled image's pixels, and the part of the image it reads.
  m.map_x.create(n_t, n_s, CV_32FC1);
  m.map_y.create(n_t, n_s, CV_32FC1);
  float x_lo = 1e30f, x_hi = -1e30f, y_lo = 1e30f, y_hi = -1e30f;
  const float scale = 1.0f / float(reduction), shift = 0.5f / float(reduction) - 0.5f;
  for (int l = 0; l < n_t; ++l) {
    float* mx = m.map_x.ptr<float>(l);
    float* my = m.map_y.ptr<float>(l);
    for (int kk = 0; kk < n_s; ++kk) {
      const Vec2 p = pixel_of(kk, l);
      mx[kk] = float(p.x()) * scale + shift;
      my[kk] = float(p.y()) * scale + shift;
      if (mx[kk] >= -1 && mx[kk] <= scaled.width && my[kk] >= -1 && my[kk] <= scaled.height) {
        x_lo = std::min(x_lo, mx[kk]);
        x_hi = std::max(x_hi, mx[kk]);
        y_lo = std::min(y_lo, my[kk]);
        y_hi = std::max(y_hi, my[kk]);
      }
    }
  }
  // A margin for the interpolation kernel (Lanczos reaches 4 pixels) and the prefilter.
  const int margin = 5 + int(std::ceil(m.footprint / reduction));
  m.wanted =
      x_hi < x_lo
          ? cv::Rect()
          : cv::Rect(
                cv::Point(int(std::floor(x_lo)) - margin, int(std::floor(y_lo)) - margin),
                cv::Point(int(std::ceil(x_hi)) + margin + 1, int(std::ceil(y_hi)) + margin + 1)) &
                cv::Rect(cv::Point(0, 0), scaled);
  return m;
}

// Resamples one camera's image into its view through its map. Returns the decode reduction used.
int BuildView(const ViewJob& job, ViewMap& view_map, StOffset window, const BuildOptions& options,
              std::uint8_t* view, ViewStats* stats, double* decode_seconds) {
  const int n_s = options.n_s, n_t = options.n_t;
  const CameraIntrinsics& k = job.camera->intrinsics;
  const int reduction = view_map.reduction;
  const double footprint = view_map.footprint;
  const cv::Size scaled = view_map.scaled;
  const cv::Rect wanted = view_map.wanted;
  cv::Mat& map_x = view_map.map_x;
  cv::Mat& map_y = view_map.map_y;

  const std::vector<std::uint8_t> bytes = job.image->read();
  const std::string& name = job.image->name;
  ImageHeader header;
  try {
    header = ProbeImageHeader(bytes);
  } catch (const Error& e) {
    throw Error(fmt::format("{} ({}): {}", name, CameraLabel(job.row, job.col), e.what()));
  }
  if (header.width != k.width || header.height != k.height)
    throw Error(fmt::format("{} ({}): the image is {}x{}, but the calibration is for {}x{} images",
                            name, CameraLabel(job.row, job.col), header.width, header.height,
                            k.width, k.height));
  const auto start = std::chrono::steady_clock::now();
  const DecodedRegion region = DecodeRegion(bytes, name, reduction, scaled, wanted, options.chroma);
  *decode_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  cv::Mat sampled(n_t, n_s, CV_32FC3, cv::Scalar(0, 0, 0));
  const PhotometricCorrection identity;
  const PhotometricCorrection& photometry =
      options.photometric_correction && job.camera->photometry ? *job.camera->photometry : identity;
  const cv::Rect& roi = region.roi;
  if (roi.area() > 0) {
    // The region in linear light, photometrically corrected: 1 / (gain * falloff), the falloff's
    // row term hoisted.
    const auto& lut = SrgbDecodeTable();
    cv::Mat linear(roi.size(), CV_32FC3);
    const Vec3 inverse_gain = photometry.gain.cwiseInverse();
    const float gain_r = float(inverse_gain.x()), gain_g = float(inverse_gain.y()),
                gain_b = float(inverse_gain.z());
    const float per_pixel2 = float(photometry.falloff_per_pixel2(k));
    std::vector<float> dx2(std::size_t(roi.width));
    for (int x = 0; x < roi.width; ++x) {
      const double dx = (roi.x + x + 0.5) * reduction - 0.5 - k.cx;
      dx2[std::size_t(x)] = float(dx * dx);
    }
    for (int y = 0; y < roi.height; ++y) {
      const auto* in = region.rgb.ptr<cv::Vec3b>(y);
      auto* out = linear.ptr<cv::Vec3f>(y);
      const double dy = (roi.y + y + 0.5) * reduction - 0.5 - k.cy;
      const float dy2 = float(dy * dy);
      for (int x = 0; x < roi.width; ++x) {
        const float f = 1.0f / (1.0f + per_pixel2 * (dx2[std::size_t(x)] + dy2));
        out[x] = cv::Vec3f(lut[in[x][0]] * gain_r * f, lut[in[x][1]] * gain_g * f,
                           lut[in[x][2]] * gain_b * f);
      }
    }
    // What the scaled decode left of the shrink: a Gaussian prefilter.
    const double remaining = footprint / reduction;
    if (remaining > 1.25) {
      const double sigma = 0.5 * std::sqrt(remaining * remaining - 1.0);
      cv::GaussianBlur(linear, linear, cv::Size(), sigma, sigma, cv::BORDER_REPLICATE);
    }
    map_x -= float(roi.x);
    map_y -= float(roi.y);
    const int interpolation = options.resampling == Resampling::kLinear  ? cv::INTER_LINEAR
                              : options.resampling == Resampling::kCubic ? cv::INTER_CUBIC
                                                                         : cv::INTER_LANCZOS4;
    cv::remap(linear, sampled, map_x, map_y, interpolation, cv::BORDER_CONSTANT,
              cv::Scalar(0, 0, 0));
    map_x += float(roi.x);
    map_y += float(roi.y);
  }
  // Encode the view (row l = 0 at the bottom of the st domain, as the map's rows are).
  const auto& encode = LinearToSrgb8EncodeTable();
  for (int l = 0; l < n_t; ++l) {
    const auto* in = sampled.ptr<cv::Vec3f>(l);
    std::uint8_t* out = view + std::size_t(l) * std::size_t(n_s) * 3;
    for (int kk = 0; kk < n_s; ++kk)
      for (int ch = 0; ch < 3; ++ch) out[kk * 3 + ch] = LinearToSrgb8With(encode, in[kk][ch]);
  }
  // Colour statistics on the coarse grid of the reference window (the st domain): inside the
  // view's window and its image, with and without the correction.
  for (int ref_l = 0, i = 0; ref_l < n_t; ref_l += kStatsStride)
    for (int ref_k = 0; ref_k < n_s; ref_k += kStatsStride, ++i) {
      const int kk = ref_k - window.k, l = ref_l - window.l;
      if (kk < 0 || l < 0 || kk >= n_s || l >= n_t) continue;
      const float mx = map_x.at<float>(l, kk), my = map_y.at<float>(l, kk);
      const bool inside = mx >= 1 && my >= 1 && mx <= scaled.width - 2 && my <= scaled.height - 2;
      stats->valid[std::size_t(i)] = inside;
      if (!inside) continue;
      const cv::Vec3f v = sampled.at<cv::Vec3f>(l, kk);
      const Vec3 after(v[0], v[1], v[2]);
      const double full_x = (mx + 0.5) * reduction - 0.5, full_y = (my + 0.5) * reduction - 0.5;
      stats->after[std::size_t(i)] = after;
      stats->before[std::size_t(i)] =
          after.cwiseProduct(photometry.gain) * photometry.falloff(k, full_x, full_y);
    }
  return reduction;
}

// Where a view's window lies: the reference grid moved by whole samples so that its centre is
// nearest where the camera's image centre looks (its pinhole's line; distortion is negligible
// there). (0, 0) for a camera whose line misses the plane.
StOffset ViewWindowOffset(const StSampling& reference, const Rigid3& world_from_camera,
                          const CameraIntrinsics& k) {
  const Vec3 in_camera(((k.width - 1) * 0.5 - k.cx) / k.fx, ((k.height - 1) * 0.5 - k.cy) / k.fy,
                       1.0);
  const Vec3 direction = world_from_camera.rotation * in_camera;
  const Vec3& centre = world_from_camera.translation;
  const Vec3 normal = reference.window.normal();
  const double along = normal.dot(direction);
  if (!(std::abs(along) > 1e-12)) return {};
  const double lambda = normal.dot(reference.window.origin - centre) / along;
  if (!(lambda > 0)) return {};
  const Vec2 at = reference.SampleOf(centre + lambda * direction);
  const double k_off = at.x() - 0.5 * (reference.n_s - 1),
               l_off = at.y() - 0.5 * (reference.n_t - 1);
  if (!(std::abs(k_off) < kMaxStOffset && std::abs(l_off) < kMaxStOffset)) return {};
  return {int(std::lround(k_off)), int(std::lround(l_off))};
}

ColourSpread Spread(const std::vector<ViewStats>& stats, const std::vector<bool>& built,
                    bool before) {
  ColourSpread out;
  const std::size_t cells = stats.empty() ? 0 : stats[0].valid.size();
  std::vector<std::uint8_t> common(cells, 1);
  for (std::size_t v = 0; v < stats.size(); ++v)
    if (built[v])
      for (std::size_t i = 0; i < cells; ++i) common[i] &= stats[v].valid[i];
  const auto region = std::count(common.begin(), common.end(), 1);
  out.region_fraction = cells ? double(region) / double(cells) : 0;
  if (region == 0) return out;
  std::vector<Vec3> means;
  for (std::size_t v = 0; v < stats.size(); ++v) {
    if (!built[v]) continue;
    Vec3 sum = Vec3::Zero();
    for (std::size_t i = 0; i < cells; ++i)
      if (common[i]) sum += before ? stats[v].before[i] : stats[v].after[i];
    means.push_back(sum / double(region));
  }
  out.cameras = int(means.size());
  Vec3 median;
  for (int ch = 0; ch < 3; ++ch) {
    std::vector<double> values;
    for (const Vec3& m : means) values.push_back(m[ch]);
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(values.size() / 2),
                     values.end());
    median[ch] = values[values.size() / 2];
  }
  double sum2 = 0;
  for (const Vec3& m : means)
    for (int ch = 0; ch < 3; ++ch) {
      const double deviation = median[ch] > 0 ? m[ch] / median[ch] - 1 : 0;
      out.max_deviation = std::max(out.max_deviation, std::abs(deviation));
      sum2 += deviation * deviation;
    }
  out.rms_deviation = std::sqrt(sum2 / (3.0 * double(means.size())));
  return out;
}

}  // namespace

Resampling ResamplingFromString(const std::string& name) {
  if (name == "linear") return Resampling::kLinear;
  if (name == "cubic") return Resampling::kCubic;
  if (name == "lanczos4") return Resampling::kLanczos4;
  throw Error(fmt::format("'{}' is not a resampling kernel (linear, cubic, lanczos4)", name));
}

std::string ToString(Resampling resampling) {
  switch (resampling) {
    case Resampling::kLinear:
      return "linear";
    case Resampling::kCubic:
      return "cubic";
    case Resampling::kLanczos4:
      return "lanczos4";
  }
  return "?";
}

LightField BuildLightField(const std::filesystem::path& dir, const CaptureManifest& manifest,
                           const CalibrationFile& cal, const BuildOptions& o,
                           BuildReport* report_out) {
  if (manifest.rows != cal.rows || manifest.cols != cal.cols)
    throw Error(fmt::format("the calibration is for a {}x{} array, the session has {}x{}", cal.rows,
                            cal.cols, manifest.rows, manifest.cols));
  if (manifest.sensor_width != cal.width || manifest.sensor_height != cal.height)
    throw Error(fmt::format("the calibration is for {}x{} images, the session's are {}x{}",
                            cal.width, cal.height, manifest.sensor_width, manifest.sensor_height));
  const Shot* shot = nullptr;
  for (const Shot& s : manifest.shots)
    if (s.name == o.shot) shot = &s;
  if (!shot)
    throw Error(fmt::format("{}: the session has no shot named '{}'",
                            (dir / kManifestName).string(), o.shot));
  if (shot->kind == ShotKind::kVideo)
    throw Error(
        fmt::format("shot '{}' is a recording: its light field is a video "
                    "(BuildLightFieldVideo)",
                    o.shot));
  std::vector<CameraImage> images;
  for (const ShotImage& image : shot->images) {
    const std::filesystem::path path = dir / image.file;
    images.push_back({image.row, image.col, path.string(),
                      [path] { return ReadFileBytes(path, kMaxEncodedImageBytes, "image file"); }});
  }
  LightField lf =
      BuildLightFieldFromImages(cal, images, fmt::format("in shot '{}'", o.shot), o, report_out);
  lf.metadata()["shot"] = o.shot;
  lf.metadata()["session"] = manifest.source;
  return lf;
}

LightField BuildLightFieldFromImages(const CalibrationFile& cal,
                                     const std::vector<CameraImage>& images,
                                     const std::string& where, const BuildOptions& o,
                                     BuildReport* report_out, std::vector<ViewMap>* maps) {
  const auto start = std::chrono::steady_clock::now();
  if (maps && maps->size() != cal.cameras.size()) maps->assign(cal.cameras.size(), ViewMap{});
  BuildReport report;
  if (o.n_s < 1 || o.n_t < 1 || o.n_s > kMaxStSamplesPerSide || o.n_t > kMaxStSamplesPerSide)
    throw Error(fmt::format("st resolution {}x{} is out of range", o.n_s, o.n_t));
  Slab slab = cal.slab;
  if (o.st_domain) slab.st_domain = *o.st_domain;
  slab.validate();
  const int rows = cal.rows, cols = cal.cols;
  RequireMemory(double(rows) * cols * o.n_s * o.n_t * 3,
                fmt::format("a {}x{} light field of {}x{} samples", rows, cols, o.n_s, o.n_t));

  // Which views can be built, and why not the others.
  std::vector<const CameraImage*> image_of(std::size_t(rows) * std::size_t(cols), nullptr);
  for (const CameraImage& image : images) {
    if (image.row < 0 || image.col < 0 || image.row >= rows || image.col >= cols)
      throw Error(fmt::format("{}: {} is outside the calibration's {}x{} grid", image.name,
                              CameraLabel(image.row, image.col), rows, cols));
    image_of[std::size_t(image.row * cols + image.col)] = &image;
  }
  std::vector<ViewJob> jobs;
  std::vector<bool> built(image_of.size(), false);
  std::vector<std::string> missing;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const std::size_t i = std::size_t(r * cols + c);
      const CalibratedCamera& camera = cal.cameras[i];
      if (!image_of[i])
        missing.push_back(fmt::format("{}: no image {}", CameraLabel(r, c), where));
      else if (!camera.calibrated)
        missing.push_back(
            fmt::format("{}: not calibrated ({})", CameraLabel(r, c),
                        camera.reason.empty() ? "see the calibration" : camera.reason));
      else {
        jobs.push_back({r, c, &camera, image_of[i]});
        built[i] = true;
      }
    }
  if (!missing.empty() && !o.allow_missing)
    throw Error(
        fmt::format("{} of {} cameras cannot be built (--allow-missing fills them from "
                    "their neighbours):\n  {}",
                    missing.size(), image_of.size(), fmt::join(missing, "\n  ")));
  if (jobs.empty()) throw Error("no camera of the session can be built");

  LightField lf({rows, cols, o.n_s, o.n_t}, SampleType::kSrgb8, slab);
  if (o.view_windows) {
    // Each camera's window; a camera that is not built takes the plane through the built ones'
    // (the windows move linearly across a rigid array), or its nearest neighbour's.
    std::vector<StOffset> offsets(image_of.size());
    Eigen::MatrixXd a(Eigen::Index(jobs.size()), 3);
    Eigen::MatrixXd b(Eigen::Index(jobs.size()), 2);
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      const std::size_t i = std::size_t(jobs[j].row * cols + jobs[j].col);
      offsets[i] = ViewWindowOffset(lf.st_sampling(), cal.cameras[i].world_from_camera,
                                    cal.cameras[i].intrinsics);
      a.row(Eigen::Index(j)) << 1.0, jobs[j].col, jobs[j].row;
      b.row(Eigen::Index(j)) << offsets[i].k, offsets[i].l;
    }
    const bool plane = MatrixRank(a) == 3;
    const Eigen::MatrixXd fit = plane ? SolveLeastSquares(a, b) : Eigen::MatrixXd();
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const std::size_t i = std::size_t(r * cols + c);
        if (built[i]) continue;
        if (plane) {
          const Eigen::RowVector2d at = Eigen::RowVector3d(1.0, c, r) * fit;
          offsets[i] = {int(std::lround(at(0))), int(std::lround(at(1)))};
        } else {
          const auto from = NearestPresentViews(rows, cols, built, r, c);
          offsets[i] = offsets[std::size_t(from[0].first * cols + from[0].second)];
        }
      }
    lf.set_st_offsets(std::move(offsets));
  }
  const std::size_t cells = std::size_t((o.n_s + kStatsStride - 1) / kStatsStride) *
                            std::size_t((o.n_t + kStatsStride - 1) / kStatsStride);
  std::vector<ViewStats> stats(image_of.size());
  std::mutex mutex;
  std::vector<std::string> unreadable;
  std::atomic<int> reduction_max{1};
  double decode_seconds = 0;
  tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t j) {
    const ViewJob& job = jobs[j];
    ViewStats& s = stats[std::size_t(job.row * cols + job.col)];
    s.valid.assign(cells, 0);
    s.after.assign(cells, Vec3::Zero());
    s.before.assign(cells, Vec3::Zero());
    double decode = 0;
    int reduction = 1;
    try {
      ViewMap local;
      ViewMap* map = maps ? &(*maps)[std::size_t(job.row * cols + job.col)] : &local;
      if (map->map_x.empty()) *map = MakeViewMap(*job.camera, lf.st_sampling(job.row, job.col), o);
      reduction = BuildView(job, *map, lf.st_offset(job.row, job.col), o,
                            lf.mutable_view_data(job.row, job.col), &s, &decode);
    } catch (const Error& e) {
      // An image that cannot be read: filled like a missing one when that is allowed.
      if (!o.allow_missing) throw;
      std::lock_guard lock(mutex);
      built[std::size_t(job.row * cols + job.col)] = false;
      unreadable.push_back(e.what());
      s.valid.assign(cells, 0);
      return;
    }
    std::lock_guard lock(mutex);
    decode_seconds += decode;
    reduction_max = std::max(reduction_max.load(), reduction);
    if (o.view_done) o.view_done();
  });
  if (std::none_of(built.begin(), built.end(), [](bool b) { return b; }))
    throw Error(fmt::format("no camera's image {} could be read:\n  {}", where,
                            fmt::join(unreadable, "\n  ")));
  // Views too dark to be photographs of the scene: filled like missing ones, at their own poses.
  std::vector<bool> dark(image_of.size(), false);
  nlohmann::json dark_views = nlohmann::json::array();
  if (o.fill_dark_views)
    for (const auto& [r, c] : DarkViews(lf, built)) {
      const std::size_t i = std::size_t(r * cols + c);
      built[i] = false;
      dark[i] = true;
      report.dark.emplace_back(r, c);
      dark_views.push_back({{"row", r}, {"col", c}});
    }
  report.unreadable = unreadable;
  report.decode_seconds = decode_seconds;
  report.reduction_max = reduction_max;
  report.before = Spread(stats, built, true);
  report.after = Spread(stats, built, false);

  // Measured poses; missing views filled from their nearest built neighbours, in linear light.
  std::vector<ViewPose> poses(image_of.size());
  for (std::size_t i = 0; i < image_of.size(); ++i)
    if (built[i] || dark[i]) {
      // The camera as `render --as-camera` reproduces it: its pinhole, distortion undone.
      CameraIntrinsics pinhole = cal.cameras[i].intrinsics;
      pinhole.distortion = {};
      poses[i] = {cal.cameras[i].world_from_camera.translation,
                  cal.cameras[i].world_from_camera.rotation, pinhole};
    }
  nlohmann::json filled = nlohmann::json::array();
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const std::size_t i = std::size_t(r * cols + c);
      if (built[i]) continue;
      const auto from = NearestPresentViews(rows, cols, built, r, c);
      FillViewWithMean(lf, r, c, from);
      const ViewPose& nearest = poses[std::size_t(from[0].first * cols + from[0].second)];
      if (!dark[i])
        poses[i] = {slab.uv.camera_center(r, c), nearest.orientation, nearest.intrinsics};
      report.filled.push_back(FilledViewLabel(r, c, from));
      filled.push_back({{"row", r}, {"col", c}, {"from", from}});
    }
  lf.set_measured_poses(std::move(poses));
  const auto now = std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now());
  auto spread_json = [](const ColourSpread& s) {
    return nlohmann::json{{"max_deviation", s.max_deviation},
                          {"rms_deviation", s.rms_deviation},
                          {"cameras", s.cameras},
                          {"region_fraction", s.region_fraction}};
  };
  nlohmann::json corrections = nlohmann::json::array();
  for (const CalibratedCamera& camera : cal.cameras)
    if (camera.photometry && o.photometric_correction)
      corrections.push_back({{"row", camera.row},
                             {"col", camera.col},
                             {"photometry", PhotometryToJson(*camera.photometry)}});
  lf.metadata() = {{"source", "built"},
                   {"resampling", ToString(o.resampling)},
                   {"chroma_upsampling", ToString(o.chroma)},
                   {"calibration", cal.summary},
                   {"color_correction",
                    {{"applied", o.photometric_correction && !corrections.empty()},
                     {"cameras", corrections},
                     {"mean_colour_spread_before", spread_json(report.before)},
                     {"mean_colour_spread_after", spread_json(report.after)}}},
                   {"filled_views", filled},
                   {"dark_views", dark_views},
                   {"unreadable_images", unreadable},
                   {"created", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", now)}};
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report_out) *report_out = report;
  return lf;
}

}  // namespace lfcam
