#include "lfcam/calib/session_detection.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <mutex>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"

namespace lfcam {
namespace {

Error MixedSizes(const std::filesystem::path& path, const ShotImage& image, int width, int height,
                 int sensor_width, int sensor_height) {
  return Error(fmt::format(
      "{} ({}): the image is {}x{}, but the session's sensor is {}x{} (images of mixed sizes)",
      path.string(), CameraLabel(image.row, image.col), width, height, sensor_width,
      sensor_height));
}

}  // namespace

SessionDetections DetectSessionBoards(const std::filesystem::path& dir,
                                      const CaptureManifest& manifest,
                                      const BoardSpec& intrinsics_board,
                                      const BoardSpec& world_board,
                                      const std::function<void()>& image_done, int min_views) {
  SessionDetections out;
  out.width = manifest.sensor_width;
  out.height = manifest.sensor_height;
  out.cameras.resize(std::size_t(manifest.rows) * std::size_t(manifest.cols));
  for (int r = 0; r < manifest.rows; ++r)
    for (int c = 0; c < manifest.cols; ++c) {
      out.camera(r, c, manifest.cols).row = r;
      out.camera(r, c, manifest.cols).col = c;
    }
  struct Job {
    const ShotImage* image;
    int intrinsics_shot;  // -1: the world shot
    std::string shot_name;
  };
  std::vector<Job> jobs;
  for (const Shot* shot : manifest.shots_of(ShotKind::kIntrinsics)) {
    for (const ShotImage& image : shot->images)
      jobs.push_back({&image, out.intrinsics_shots, shot->name});
    out.intrinsics_shot_names.push_back(shot->name);
    ++out.intrinsics_shots;
  }
  for (const Shot* shot : manifest.shots_of(ShotKind::kWorld))
    for (const ShotImage& image : shot->images) jobs.push_back({&image, -1, shot->name});

  // Every image's size from its header first (a few hundred bytes each): a session of mixed sizes
  // is refused before minutes of searching, naming the first such image in the manifest's order.
  // An image whose header cannot be read is left to the search, which warns on its camera.
  for (const Job& job : jobs) {
    const auto path = dir / job.image->file;
    ImageHeader header;
    try {
      header = ProbeImageFile(path);
    } catch (const Error&) {
      continue;
    }
    if (header.width != out.width || header.height != out.height)
      throw MixedSizes(path, *job.image, header.width, header.height, out.width, out.height);
  }

  std::mutex mutex;
  std::optional<Error> mixed_sizes;
  // Searches one image; returns whether its board was found.
  auto search = [&](const Job& job, bool thorough) {
    const auto path = dir / job.image->file;
    std::optional<std::vector<cv::Point2f>> corners;
    std::string warning;
    bool not_found = false;
    try {
      const cv::Mat gray = ReadImageGray8(path);
      if (gray.cols != out.width || gray.rows != out.height) {
        std::lock_guard lock(mutex);
        if (!mixed_sizes)
          mixed_sizes = MixedSizes(path, *job.image, gray.cols, gray.rows, out.width, out.height);
      } else {
        const BoardSpec& board = job.intrinsics_shot >= 0 ? intrinsics_board : world_board;
        BoardDetectionOptions options;
        options.thorough = thorough;
        corners = DetectBoard(gray, board, options);
        not_found = !corners;
      }
    } catch (const Error& e) {
      warning = fmt::format("{}: unreadable image: {}", job.shot_name, e.what());
    }
    std::lock_guard lock(mutex);
    CameraDetections& camera = out.camera(job.image->row, job.image->col, manifest.cols);
    if (!warning.empty()) camera.warnings.push_back(warning);
    if (corners) {
      if (job.intrinsics_shot >= 0)
        camera.intrinsics.push_back({job.intrinsics_shot, std::move(*corners)});
      else
        camera.world = std::move(*corners);
    }
    return !not_found;
  };

  // First pass: the plain detector on every image (fast, also where the board is partly out of
  // view, which is most misses).
  std::vector<char> missed(jobs.size(), 0);
  tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t index) {
    missed[index] = !search(jobs[index], false);
    if (image_done) {
      std::lock_guard lock(mutex);
      image_done();
    }
  });
  // Second pass, thorough, where a miss hurts: the world board of every camera that missed it,
  // and every missed intrinsics image of a camera left with too few views. When a board was
  // found in no image at all, the board is most likely not the one named (a wrong SPEC): a
  // sample of images is tried thoroughly first, and the rest only if the sample finds it.
  auto found_any = [&](bool intrinsics) {
    for (std::size_t i = 0; i < jobs.size(); ++i)
      if ((jobs[i].intrinsics_shot >= 0) == intrinsics && !missed[i]) return true;
    return false;
  };
  const bool intrinsics_found = found_any(true), world_found = found_any(false);
  std::vector<std::size_t> retry, sample;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (!missed[i]) continue;
    const bool intrinsics = jobs[i].intrinsics_shot >= 0;
    const CameraDetections& camera =
        out.camera(jobs[i].image->row, jobs[i].image->col, manifest.cols);
    if (intrinsics && int(camera.intrinsics.size()) >= min_views) continue;
    if (intrinsics ? intrinsics_found : world_found)
      retry.push_back(i);
    else
      sample.push_back(i);
  }
  // The sample: a few images of each kind, spread over the session.
  constexpr std::size_t kSample = 6;
  std::vector<std::size_t> sampled, rest;
  for (const bool intrinsics : {true, false}) {
    std::vector<std::size_t> kind;
    for (const std::size_t i : sample)
      if ((jobs[i].intrinsics_shot >= 0) == intrinsics) kind.push_back(i);
    for (std::size_t k = 0; k < kind.size(); ++k)
      (k % std::max<std::size_t>(1, kind.size() / kSample) == 0 ? sampled : rest)
          .push_back(kind[k]);
  }
  auto retry_all = [&](const std::vector<std::size_t>& list) {
    std::atomic<int> found{0};
    tbb::parallel_for(std::size_t(0), list.size(), [&](std::size_t r) {
      if (search(jobs[list[r]], true)) {
        missed[list[r]] = 0;
        ++found;
      }
    });
    return found.load();
  };
  retry_all(retry);
  if (retry_all(sampled) > 0) retry_all(rest);
  for (std::size_t i = 0; i < jobs.size(); ++i)
    if (missed[i])
      out.camera(jobs[i].image->row, jobs[i].image->col, manifest.cols)
          .not_found.push_back(jobs[i].shot_name);
  if (mixed_sizes) throw *mixed_sizes;
  for (auto& camera : out.cameras)
    std::sort(camera.intrinsics.begin(), camera.intrinsics.end(),
              [](const BoardView& a, const BoardView& b) { return a.shot < b.shot; });
  return out;
}

}  // namespace lfcam
