#include "lfcam/session/session.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>

#include "lfcam/core/error.h"
#include "lfcam/core/image_header.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"

namespace lfcam {

std::string ToString(ShotKind kind) {
  switch (kind) {
    case ShotKind::kIntrinsics:
      return "intrinsics";
    case ShotKind::kWorld:
      return "world";
    case ShotKind::kScene:
      return "scene";
    case ShotKind::kVideo:
      return "video";
  }
  return "?";
}

std::vector<const Shot*> CaptureManifest::shots_of(ShotKind kind) const {
  std::vector<const Shot*> out;
  for (const Shot& s : shots)
    if (s.kind == kind) out.push_back(&s);
  return out;
}

std::string CameraFileName(int row, int col) {
  return fmt::format("cam_{:02d}_{:02d}.jpg", row, col);
}

std::string ToString(ImageStatus status) {
  switch (status) {
    case ImageStatus::kOk:
      return "ok";
    case ImageStatus::kCaptured:
      return "captured";
    case ImageStatus::kMissing:
      return "missing";
  }
  return "?";
}

std::string CameraLabel(int row, int col) { return fmt::format("camera ({}, {})", row, col); }

nlohmann::json ManifestToJson(const CaptureManifest& m) {
  nlohmann::json shots = nlohmann::json::array();
  for (const Shot& s : m.shots) {
    nlohmann::json images = nlohmann::json::array();
    for (const auto* list : {&s.images, &s.pending})
      for (const ShotImage& i : *list) {
        nlohmann::json image = {{"row", i.row}, {"col", i.col}, {"file", i.file}};
        if (i.status != ImageStatus::kOk) image["status"] = ToString(i.status);
        if (!i.capture.is_null()) image["capture"] = i.capture;
        if (!i.frames.empty()) {
          nlohmann::json frames = nlohmann::json::array();
          for (const FrameTime& f : i.frames)
            frames.push_back({f.sequence, f.offset, f.size, f.wall_clock_ns, f.sensor_ns});
          image["frames"] = std::move(frames);
        }
        images.push_back(std::move(image));
      }
    nlohmann::json shot = {{"kind", ToString(s.kind)}, {"name", s.name}, {"images", images}};
    if (s.video)
      shot["video"] = {
          {"fps", s.video->fps},
          {"seconds", s.video->seconds},
          {"width", s.video->width},
          {"height", s.video->height},
          {"sync", s.video->sync},
          {"start_unix_ns", s.video->start_unix_ns},
          {"groups", s.video->groups},
          {"frame_columns", {"sequence", "offset", "size", "wall_clock_ns", "sensor_ns"}}};
    shots.push_back(std::move(shot));
  }
  nlohmann::json boards = nlohmann::json::object();
  if (m.intrinsics_board) boards["intrinsics"] = BoardToJson(*m.intrinsics_board);
  if (m.world_board) boards["world"] = BoardToJson(*m.world_board);
  return {{"format", "lfcam-capture"},
          {"version", kManifestVersion},
          {"grid", {{"rows", m.rows}, {"cols", m.cols}, {"pitch_mm", m.pitch_mm}}},
          {"sensor",
           {{"width", m.sensor_width}, {"height", m.sensor_height}, {"model", m.sensor_model}}},
          {"boards", boards},
          {"shots", shots},
          {"source", m.source}};
}

namespace {

ShotKind ShotKindFromString(const std::string& text, const std::string& where) {
  if (text == "intrinsics") return ShotKind::kIntrinsics;
  if (text == "world") return ShotKind::kWorld;
  if (text == "scene") return ShotKind::kScene;
  if (text == "video") return ShotKind::kVideo;
  throw Error(
      fmt::format("{}: shot kind '{}' is not intrinsics, world, scene or video", where, text));
}

VideoShot VideoShotFromJson(const nlohmann::json& j, const std::string& where) {
  VideoShot v;
  v.fps = JsonNumber(j, "fps", where);
  v.seconds = JsonNumber(j, "seconds", where);
  if (!(v.fps > 0 && v.fps <= 1000) || !(v.seconds > 0 && v.seconds <= 86400))
    throw Error(fmt::format("{}: fps must be in (0, 1000] and seconds in (0, 86400]", where));
  v.width = int(JsonInteger(j, "width", 1, kMaxImageSide, where));
  v.height = int(JsonInteger(j, "height", 1, kMaxImageSide, where));
  v.sync = JsonString(j, "sync", where);
  if (v.sync != "on" && v.sync != "off")
    throw Error(fmt::format("{}: sync '{}' is not on or off", where, v.sync));
  v.start_unix_ns = JsonInteger(j, "start_unix_ns", 0, INT64_MAX, where);
  v.groups = int(JsonInteger(j, "groups", 1, 64, where));
  return v;
}

}  // namespace

std::vector<FrameTime> FramesFromJson(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array()) throw Error(fmt::format("{}: frames must be an array", where));
  std::vector<FrameTime> out;
  out.reserve(j.size());
  for (std::size_t k = 0; k < j.size(); ++k) {
    const nlohmann::json& f = j[k];
    const std::string fw = fmt::format("{}: frames[{}]", where, k);
    if (!f.is_array() || f.size() != 5 ||
        !std::all_of(f.begin(), f.end(), [](const auto& x) { return x.is_number_integer(); }))
      throw Error(fmt::format(
          "{}: a frame is [sequence, offset, size, wall_clock_ns, sensor_ns], integers", fw));
    FrameTime t;
    t.sequence = f[0].get<std::int64_t>();
    t.offset = f[1].get<std::uint64_t>();
    t.size = f[2].get<std::uint64_t>();
    t.wall_clock_ns = f[3].get<std::int64_t>();
    t.sensor_ns = f[4].get<std::int64_t>();
    if (t.sequence < 0 || t.wall_clock_ns < 0 || t.size < 4 || t.size > kMaxEncodedImageBytes ||
        f[1].get<std::int64_t>() < 0)
      throw Error(fmt::format("{}: a negative number or a frame size out of range", fw));
    if (!out.empty()) {
      const FrameTime& before = out.back();
      if (t.sequence <= before.sequence || t.wall_clock_ns <= before.wall_clock_ns ||
          t.offset != before.offset + before.size)
        throw Error(fmt::format(
            "{}: frame {} does not follow frame {} (sequence and time increase, bytes back to "
            "back)",
            fw, t.sequence, before.sequence));
    } else if (t.offset != 0) {
      throw Error(fmt::format("{}: the first frame must start at byte 0", fw));
    }
    out.push_back(t);
  }
  return out;
}

namespace {

// A relative, '/'-separated path with no empty, "." or ".." parts and no NUL.
void CheckRelativeName(const std::string& file, const std::string& where) {
  if (file.empty() || file.size() > 1024 || file.front() == '/' ||
      file.find('\0') != std::string::npos || file.find('\\') != std::string::npos)
    throw Error(
        fmt::format("{}: file name '{}' must be a relative path inside the session", where, file));
  std::size_t start = 0;
  while (start <= file.size()) {
    const std::size_t slash = std::min(file.find('/', start), file.size());
    const std::string part = file.substr(start, slash - start);
    if (part.empty() || part == "." || part == "..")
      throw Error(fmt::format("{}: file name '{}' must be a relative path inside the session",
                              where, file));
    start = slash + 1;
  }
}

}  // namespace

CaptureManifest ManifestFromJson(const nlohmann::json& j, const std::string& where) {
  JsonFormatVersion(j, "lfcam-capture", kManifestVersion, "capture manifest", where);
  CaptureManifest m;
  const auto& grid = JsonField(j, "grid", where);
  m.rows = int(JsonInteger(grid, "rows", 1, kMaxViewsPerSide, where + ": grid"));
  m.cols = int(JsonInteger(grid, "cols", 1, kMaxViewsPerSide, where + ": grid"));
  m.pitch_mm = JsonNumber(grid, "pitch_mm", where + ": grid");
  if (!(m.pitch_mm > 0 && m.pitch_mm < 1e6))
    throw Error(fmt::format("{}: grid: pitch_mm {} must be positive", where, m.pitch_mm));
  const auto& sensor = JsonField(j, "sensor", where);
  m.sensor_width = int(JsonInteger(sensor, "width", 1, kMaxImageSide, where + ": sensor"));
  m.sensor_height = int(JsonInteger(sensor, "height", 1, kMaxImageSide, where + ": sensor"));
  if (sensor.contains("model")) m.sensor_model = JsonString(sensor, "model", where + ": sensor");
  if (j.contains("boards")) {
    const auto& boards = j["boards"];
    if (!boards.is_object()) throw Error(fmt::format("{}: boards must be an object", where));
    if (boards.contains("intrinsics"))
      m.intrinsics_board = BoardFromJson(boards["intrinsics"], where + ": boards: intrinsics");
    if (boards.contains("world"))
      m.world_board = BoardFromJson(boards["world"], where + ": boards: world");
  }
  const auto& shots = JsonField(j, "shots", where);
  if (!shots.is_array()) throw Error(fmt::format("{}: shots must be an array", where));
  std::set<std::string> names;
  for (std::size_t s = 0; s < shots.size(); ++s) {
    const std::string sw = fmt::format("{}: shots[{}]", where, s);
    Shot shot;
    shot.kind = ShotKindFromString(JsonString(shots[s], "kind", sw), sw);
    shot.name = JsonString(shots[s], "name", sw);
    if (!names.insert(shot.name).second)
      throw Error(fmt::format("{}: shot name '{}' is used twice", sw, shot.name));
    if (shot.kind == ShotKind::kVideo)
      shot.video = VideoShotFromJson(JsonField(shots[s], "video", sw), sw + ": video");
    const auto& images = JsonField(shots[s], "images", sw);
    if (!images.is_array()) throw Error(fmt::format("{}: images must be an array", sw));
    std::set<std::pair<int, int>> seen;
    for (std::size_t i = 0; i < images.size(); ++i) {
      const std::string iw = fmt::format("{}: images[{}]", sw, i);
      ShotImage image;
      image.row = int(JsonInteger(images[i], "row", 0, m.rows - 1, iw));
      image.col = int(JsonInteger(images[i], "col", 0, m.cols - 1, iw));
      image.file = JsonString(images[i], "file", iw);
      CheckRelativeName(image.file, iw);
      if (images[i].contains("status")) {
        const std::string status = JsonString(images[i], "status", iw);
        if (status == "captured")
          image.status = ImageStatus::kCaptured;
        else if (status == "missing")
          image.status = ImageStatus::kMissing;
        else if (status != "ok")
          throw Error(fmt::format("{}: status '{}' is not ok, captured or missing", iw, status));
      }
      if (images[i].contains("capture")) {
        image.capture = images[i]["capture"];
        if (!image.capture.is_object())
          throw Error(fmt::format("{}: capture must be an object", iw));
      }
      if (images[i].contains("frames")) {
        if (shot.kind != ShotKind::kVideo)
          throw Error(fmt::format("{}: frames belong to a video shot only", iw));
        image.frames = FramesFromJson(images[i]["frames"], iw);
      }
      if (!seen.insert({image.row, image.col}).second)
        throw Error(fmt::format("{}: {} appears twice in shot '{}'", iw,
                                CameraLabel(image.row, image.col), shot.name));
      (image.status == ImageStatus::kOk ? shot.images : shot.pending).push_back(std::move(image));
    }
    m.shots.push_back(std::move(shot));
  }
  if (j.contains("source")) m.source = j["source"];
  return m;
}

namespace {

// (row, col) from "cam_RR_CC.ext", or nullopt.
std::optional<std::pair<int, int>> CameraOfFileName(const std::string& name) {
  int row = -1, col = -1, used = 0;
  if (std::sscanf(name.c_str(), "cam_%d_%d%n", &row, &col, &used) != 2 || row < 0 || col < 0 ||
      row >= kMaxViewsPerSide || col >= kMaxViewsPerSide)
    return std::nullopt;
  std::string ext = name.substr(std::size_t(used));
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".jpg" && ext != ".jpeg" && ext != ".png") return std::nullopt;
  return std::pair{row, col};
}

// The camera images directly in `folder` (relative to the session), sorted by name.
std::vector<ShotImage> ScanShotFolder(const std::filesystem::path& dir, const std::string& folder) {
  std::vector<ShotImage> images;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir / folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (const auto camera = CameraOfFileName(name); camera && entry.is_regular_file(ec))
      images.push_back({camera->first, camera->second, folder + "/" + name});
  }
  std::sort(images.begin(), images.end(),
            [](const ShotImage& a, const ShotImage& b) { return a.file < b.file; });
  return images;
}

}  // namespace

CaptureManifest ScanSessionLayout(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  CaptureManifest m;
  std::error_code ec;
  std::vector<std::string> shot_folders;
  for (const auto& entry : fs::directory_iterator(dir / "calib" / "intrinsics", ec))
    if (entry.is_directory(ec)) shot_folders.push_back(entry.path().filename().string());
  std::sort(shot_folders.begin(), shot_folders.end());
  for (const std::string& name : shot_folders) {
    Shot shot{ShotKind::kIntrinsics, name, ScanShotFolder(dir, "calib/intrinsics/" + name)};
    if (!shot.images.empty()) m.shots.push_back(std::move(shot));
  }
  Shot world{ShotKind::kWorld, "world", ScanShotFolder(dir, "calib/world")};
  if (!world.images.empty()) m.shots.push_back(std::move(world));
  Shot scene{ShotKind::kScene, "scene", ScanShotFolder(dir, "scene")};
  if (!scene.images.empty()) m.shots.push_back(std::move(scene));
  if (m.shots.empty())
    throw Error(
        fmt::format("{}: no {} and no camera images in the capture layout (calib/intrinsics/SHOT/, "
                    "calib/world/, scene/ holding cam_RR_CC.jpg; docs/capture-layout.md)",
                    dir.string(), kManifestName));
  m.rows = m.cols = 0;
  for (const Shot& shot : m.shots)
    for (const ShotImage& image : shot.images) {
      m.rows = std::max(m.rows, image.row + 1);
      m.cols = std::max(m.cols, image.col + 1);
    }
  const ShotImage& first = m.shots.front().images.front();
  const auto bytes = ReadFileBytes(dir / first.file, kMaxEncodedImageBytes, "image file");
  ImageHeader header;
  try {
    header = ProbeImageHeader(bytes);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", (dir / first.file).string(), e.what()));
  }
  m.sensor_width = header.width;
  m.sensor_height = header.height;
  m.source = {{"manifest", "read from the folder layout (no manifest.json)"}};
  return m;
}

CaptureManifest ReadManifest(const std::filesystem::path& dir) {
  const auto path = dir / kManifestName;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw Error(fmt::format("{}: not a capture session directory", dir.string()));
  if (!std::filesystem::exists(path, ec)) return ScanSessionLayout(dir);
  const auto bytes = ReadFileBytes(path, kMaxJsonBytes, "capture manifest");
  const std::string text(bytes.begin(), bytes.end());
  return ManifestFromJson(ParseJsonBounded(text, path.string()), path.string());
}

}  // namespace lfcam
