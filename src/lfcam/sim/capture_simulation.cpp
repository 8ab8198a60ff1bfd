#include "lfcam/sim/capture_simulation.h"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <chrono>
#include <mutex>
#include <numbers>
#include <random>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"
#include "lfcam/session/session.h"
#include "lfcam/sim/board_radiance.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

struct PoseRecipe {
  double distance;            // in units of the base distance
  double offset_x, offset_y;  // along u_ca, v_ca, in units of the distance
  double tilt_x, tilt_y;      // degrees, about the board's x and y axes
};

// Head-on, tilted each way, off-centre toward each corner, near and far.
constexpr PoseRecipe kRecipes[] = {
    {1.0, 0, 0, 0, 0},          {1.2, 0, 0, 25, 0},           {1.2, 0, 0, -25, 0},
    {1.2, 0, 0, 0, 25},         {1.2, 0, 0, 0, -25},          {1.1, 0.22, 0.14, 10, -15},
    {1.1, -0.22, 0.14, 10, 15}, {1.1, 0.22, -0.14, -10, -15}, {1.1, -0.22, -0.14, -10, 15},
    {0.9, 0.18, 0, 0, -20},     {0.9, -0.18, 0, 0, 20},       {1.5, 0, 0, 15, 15},
    {1.4, 0.1, -0.1, -15, 10},  {1.3, -0.1, 0.1, 20, -10},    {1.0, 0, 0.12, -20, 0},
    {1.0, 0, -0.12, 20, 0},
};

nlohmann::json RigidToJson(const Rigid3& t) {
  return {{"rotation", RotationToJson(t.rotation)},
          {"translation", {t.translation.x(), t.translation.y(), t.translation.z()}}};
}

nlohmann::json Vec3ToJson(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Removes "NAME.partial-PID" directories beside `out` whose process no longer runs.
void RemoveStalePartials(const fs::path& out) {
  const std::string prefix = out.filename().string() + ".partial-";
  std::error_code ec;
  for (const auto& entry :
       fs::directory_iterator(out.parent_path().empty() ? "." : out.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string pid_text = name.substr(prefix.size());
    char* end = nullptr;
    const long pid = std::strtol(pid_text.c_str(), &end, 10);
    if (pid_text.empty() || *end != '\0' || pid <= 0) continue;
    if (!ProcessIsGone(pid)) continue;
    fs::remove_all(entry.path(), ec);
  }
}

}  // namespace

std::vector<Rigid3> IntrinsicsBoardPoses(const ArrayPlane& array, const BoardSpec& board, int count,
                                         std::uint64_t seed) {
  const int available = int(std::size(kRecipes));
  if (count < 1 || count > available)
    throw Error(fmt::format("intrinsics shots: {} must be 1..{}", count, available));
  // The distance at which the board's width fills 40% of a module's horizontal field of view.
  const double half_fov_tan = 0.5 * kPiCameraWidth * kPiCameraPixelUm * 1e-3 / kPiCameraFocalMm;
  const double base = board.width_mm() / (0.4 * 2 * half_fov_tan);
  const Mat3 facing = [&] {
    Mat3 r;
    r.col(0) = array.u_ca;
    r.col(1) = array.v_ca;
    r.col(2) = array.n_ca;  // the board's z points toward the cameras
    return r;
  }();
  std::mt19937_64 rng(seed ^ 0xB0A4D5ull);
  auto jitter = [&rng](double half) {
    return std::uniform_real_distribution<double>(-half, half)(rng);
  };
  const double degree = std::numbers::pi / 180.0;
  std::vector<Rigid3> poses;
  for (int k = 0; k < count; ++k) {
    const PoseRecipe& p = kRecipes[k];
    const double distance = base * p.distance * (1 + jitter(0.05));
    // One draw a statement, in the order GCC has always taken them (camera_module.cpp says
    // why).
    const double turn = jitter(8), tilt_y = jitter(3), tilt_x = jitter(3);
    const Mat3 tilt = (Eigen::AngleAxisd((p.tilt_x + tilt_x) * degree, Vec3::UnitX()) *
                       Eigen::AngleAxisd((p.tilt_y + tilt_y) * degree, Vec3::UnitY()) *
                       Eigen::AngleAxisd(turn * degree, Vec3::UnitZ()))
                          .toRotationMatrix();
    const Mat3 rotation = facing * tilt;
    const Vec3 center = array.center() - distance * array.n_ca +
                        distance * (p.offset_x * array.u_ca + p.offset_y * array.v_ca);
    const Vec3 half_board(0.5 * board.width_mm(), 0.5 * board.height_mm(), 0);
    poses.push_back({rotation, center - rotation * half_board});
  }
  return poses;
}

bool SeesWholeBoard(const SimulatedModule& module, const BoardSpec& board,
                    const Rigid3& world_from_board, double margin_squares) {
  const double m = margin_squares * board.square_mm;
  const Rigid3 camera_from_world = module.world_from_camera.inverse();
  for (const Vec2& corner :
       {Vec2(-m, -m), Vec2(board.width_mm() + m, -m), Vec2(-m, board.height_mm() + m),
        Vec2(board.width_mm() + m, board.height_mm() + m)}) {
    const auto pixel = module.intrinsics.Project(
        camera_from_world * (world_from_board * Vec3(corner.x(), corner.y(), 0)));
    if (!pixel || !module.intrinsics.contains(*pixel)) return false;
  }
  return true;
}

SimulatedArray::SimulatedArray(const Scene& scene, const CaptureSimulationOptions& o)
    : scene_(scene),
      options_(o),
      array_(ResizeArray(scene.rig.array, o.rows, o.cols)),
      world_board_{scene.rig.board_inner_corners_x, scene.rig.board_inner_corners_y,
                   scene.rig.board_square_mm},
      modules_(MakeModules(array_, o.sensor_width, o.sensor_height, o.defects, o.seed)),
      board_poses_(IntrinsicsBoardPoses(array_, o.intrinsics_board, o.intrinsics_shots, o.seed)) {
  if (o.lens_blur_um) {
    if (!(*o.lens_blur_um >= 0 && *o.lens_blur_um <= kMaxLensBlurUm))
      throw Error(fmt::format("a lens blur of {} um is out of range (0..{})", *o.lens_blur_um,
                              kMaxLensBlurUm));
    for (SimulatedModule& m : modules_)
      m.lens_blur_px = LensBlurPx(*o.lens_blur_um, o.sensor_width);
  }
  auto board_plan = [&scene](ShotKind kind, std::string name, std::string dir,
                             const BoardSpec& board, const Rigid3& world_from_board) {
    return ShotPlan{kind, std::move(name), std::move(dir),
                    BoardInFrontOf(board, world_from_board, scene),
                    [board, world_from_board](const SimulatedModule& m, const cv::Mat& directions) {
                      return BoardFootprintRuns(board, world_from_board, m, directions);
                    }};
  };
  for (int k = 0; k < o.intrinsics_shots; ++k)
    plans_.push_back(board_plan(ShotKind::kIntrinsics, fmt::format("shot_{:02d}", k),
                                fmt::format("calib/intrinsics/shot_{:02d}", k), o.intrinsics_board,
                                board_poses_[std::size_t(k)]));
  // The world frame is the world board's: it stands at the identity (unless turned).
  plans_.push_back(
      board_plan(ShotKind::kWorld, "world", "calib/world", world_board_, world_from_world_board()));
  plans_.push_back({ShotKind::kScene, "scene", "scene", {}, {}});
}

Rigid3 SimulatedArray::world_from_world_board() const {
  if (!options_.world_board_turned) return {};
  return {Eigen::AngleAxisd(M_PI, Vec3::UnitZ()).toRotationMatrix(),
          Vec3(world_board_.width_mm(), world_board_.height_mm(), 0)};
}

std::optional<std::size_t> SimulatedArray::module_at(int row, int col) const {
  for (std::size_t i = 0; i < modules_.size(); ++i)
    if (modules_[i].row == row && modules_[i].col == col) return i;
  return std::nullopt;
}

std::optional<std::size_t> SimulatedArray::shot_named(const std::string& name) const {
  for (std::size_t i = 0; i < plans_.size(); ++i)
    if (plans_[i].name == name) return i;
  return std::nullopt;
}

cv::Mat SimulatedArray::Expose(std::size_t index, std::size_t s, ModuleCache& cache) const {
  const SimulatedModule& m = modules_.at(index);
  const ShotPlan& plan = plans_.at(s);
  if (cache.directions.empty()) cache.directions = ModuleRayDirections(m);
  if (cache.scene.empty())
    cache.scene =
        RenderRadiance(m, cache.directions, SceneRadiance(scene_, options_.scene_supersampling));
  ExposureOptions exposure;
  exposure.noise = options_.noise;
  exposure.noise_seed = options_.seed * 1000003ull + index * 131ull + s;
  if (!plan.radiance) return ExposeRadiance(m, cache.scene, exposure);
  const PixelRuns runs = plan.runs ? plan.runs(m, cache.directions) : PixelRuns{};
  return ExposeRadiance(
      m,
      RenderRadiance(m, cache.directions, plan.radiance, &cache.scene, plan.runs ? &runs : nullptr),
      exposure);
}

cv::Mat SimulatedArray::ExposeAt(std::size_t index, double t_seconds, std::uint64_t frame,
                                 ModuleCache& cache) const {
  const SimulatedModule& m = modules_.at(index);
  if (cache.directions.empty()) cache.directions = ModuleRayDirections(m);
  if (cache.scene.empty())
    cache.scene =
        RenderRadiance(m, cache.directions, SceneRadiance(scene_, options_.scene_supersampling));
  const Scene at = scene_.AtTime(t_seconds);
  const PixelRuns runs = SphereFootprintRuns(m, cache.directions, scene_.MovingBounds(t_seconds));
  ExposureOptions exposure;
  exposure.noise = options_.noise;
  exposure.noise_seed = options_.seed * 1000003ull + index * 131ull + (frame + 1) * 7919ull + 101;
  return ExposeRadiance(
      m,
      RenderRadiance(m, cache.directions, SceneRadiance(at, options_.scene_supersampling),
                     &cache.scene, &runs),
      exposure);
}

CaptureSimulationResult SimulateCapture(const Scene& scene, const CaptureSimulationOptions& o,
                                        const fs::path& out_dir) {
  const auto start = std::chrono::steady_clock::now();
  const SimulatedArray simulated(scene, o);
  const ArrayPlane& array = simulated.array();
  const BoardSpec& world_board = simulated.world_board();
  const std::vector<SimulatedModule>& modules = simulated.modules();
  const std::vector<Rigid3>& board_poses = simulated.intrinsics_board_poses();
  const auto& plans = simulated.shots();
  const Rigid3 world_from_world_board = simulated.world_from_world_board();

  const double image_bytes = double(o.sensor_width) * o.sensor_height;
  RequireMemory(image_bytes * (12 + 12 + 3 * 4) * 2, "simulating two camera modules at a time");

  // Stage everything in a sibling directory; rename it into place at the end.
  const fs::path out = out_dir.has_filename() ? out_dir : out_dir.parent_path();
  std::error_code exists_ec;
  if (fs::exists(out, exists_ec) &&
      (!fs::is_directory(out, exists_ec) || !fs::is_empty(out, exists_ec)))
    throw Error(fmt::format("{}: exists and is not an empty directory", out.string()));
  RemoveStalePartials(out);
  const fs::path staging = out.string() + fmt::format(".partial-{}", ::getpid());
  std::error_code ec;
  fs::remove_all(staging, ec);
  for (const auto& plan : plans) {
    fs::create_directories(staging / plan.dir, ec);
    if (ec)
      throw Error(fmt::format("{}: cannot create directory: {}", (staging / plan.dir).string(),
                              ec.message()));
  }
  struct StagingGuard {
    fs::path path;
    bool keep = false;
    ~StagingGuard() {
      std::error_code e;
      if (!keep) fs::remove_all(path, e);
    }
  } guard{staging};

  CaptureManifest manifest;
  manifest.rows = o.rows;
  manifest.cols = o.cols;
  manifest.pitch_mm = array.pitch_mm;
  manifest.sensor_width = o.sensor_width;
  manifest.sensor_height = o.sensor_height;
  manifest.sensor_model = "Raspberry Pi Camera Module v1.3 (OV5647), simulated";
  manifest.intrinsics_board = o.intrinsics_board;
  manifest.world_board = world_board;
  for (const auto& plan : plans) {
    Shot shot{plan.kind, plan.name, {}};
    for (const SimulatedModule& m : modules)
      shot.images.push_back({m.row, m.col, plan.dir + "/" + CameraFileName(m.row, m.col)});
    manifest.shots.push_back(std::move(shot));
  }
  const auto now = std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now());
  manifest.source = {{"simulator", "lfcam simulate capture"},
                     {"scene", scene.name},
                     {"seed", o.seed},
                     {"defects", o.defects == ModuleDefects::kRealistic ? "realistic" : "none"},
                     {"noise", o.noise},
                     {"created", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", now)}};

  std::mutex progress_mutex;
  tbb::parallel_for(std::size_t(0), modules.size(), [&](std::size_t index) {
    const SimulatedModule& m = modules[index];
    SimulatedArray::ModuleCache cache;
    for (std::size_t s = 0; s < plans.size(); ++s) {
      WriteImage(staging / plans[s].dir / CameraFileName(m.row, m.col),
                 simulated.Expose(index, s, cache));
      if (o.image_done) {
        std::lock_guard lock(progress_mutex);
        o.image_done();
      }
    }
  });

  // What the simulator knows, with the names calibration.json uses.
  nlohmann::json cameras = nlohmann::json::array();
  for (const SimulatedModule& m : modules) {
    cameras.push_back(nlohmann::json{
        {"row", m.row},
        {"col", m.col},
        {"intrinsics", IntrinsicsToJson(m.intrinsics)},
        {"center", Vec3ToJson(m.world_from_camera.translation)},
        {"orientation", RotationToJson(m.world_from_camera.rotation)},
        {"ideal_center", Vec3ToJson(array.camera_center(m.row, m.col))},
        {"lens_blur_px", m.lens_blur_px},
        {"photometry",
         {{"gain", Vec3ToJson(m.photometry.gain)},
          {"vignetting", {m.photometry.vignetting[0], m.photometry.vignetting[1]}}}}});
  }
  nlohmann::json shots = nlohmann::json::array();
  for (int k = 0; k < o.intrinsics_shots; ++k) {
    nlohmann::json seeing = nlohmann::json::array();
    for (const SimulatedModule& m : modules)
      if (SeesWholeBoard(m, o.intrinsics_board, board_poses[std::size_t(k)]))
        seeing.push_back({m.row, m.col});
    shots.push_back({{"name", plans[std::size_t(k)].name},
                     {"world_from_board", RigidToJson(board_poses[std::size_t(k)])},
                     {"cameras_seeing_whole_board", seeing}});
  }
  nlohmann::json slab;
  to_json(slab, Slab{array, scene.rig.board, {}});
  const nlohmann::json truth = {
      {"format", "lfcam-ground-truth"},
      {"version", 1},
      {"scene", scene.name},
      {"seed", o.seed},
      {"defects", o.defects == ModuleDefects::kRealistic ? "realistic" : "none"},
      {"ideal_array", slab},
      {"world_board",
       {{"board", BoardToJson(world_board)},
        {"world_from_board", RigidToJson(world_from_world_board)}}},
      {"intrinsics_shots", shots},
      {"cameras", cameras}};
  auto write_json = [](const fs::path& path, const nlohmann::json& j) {
    const std::string text = JsonToText(j, 2) + "\n";
    WriteFileAtomically(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
  };
  write_json(staging / kManifestName, ManifestToJson(manifest));
  write_json(staging / "ground_truth.json", truth);

  if (fs::exists(out, ec)) {
    if (!fs::is_directory(out, ec) || !fs::is_empty(out, ec))
      throw Error(fmt::format("{}: exists and is not an empty directory", out.string()));
    fs::remove(out, ec);
  }
  fs::rename(staging, out, ec);
  if (ec)
    throw Error(
        fmt::format("{}: cannot move the session into place: {}", out.string(), ec.message()));
  guard.keep = true;
  return {modules.size() * plans.size(),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

}  // namespace lfcam
