#include "lfcam/calib/array_calibration.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/parallel_for.h>

#include <Eigen/SVD>
#include <chrono>

#include "lfcam/calib/intrinsics_calibration.h"
#include "lfcam/calib/session_detection.h"
#include "lfcam/core/error.h"
#include "lfcam/session/session.h"

namespace lfcam {
namespace {

// The mean of rigid motions: the chordal mean of the rotations, the mean of the translations.
Rigid3 MeanRigid(const std::vector<Rigid3>& transforms) {
  Mat3 sum = Mat3::Zero();
  Vec3 translation = Vec3::Zero();
  for (const auto& t : transforms) {
    sum += t.rotation;
    translation += t.translation;
  }
  const Eigen::JacobiSVD<Mat3> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 rotation = svd.matrixU() * svd.matrixV().transpose();
  if (rotation.determinant() < 0) {
    Mat3 u = svd.matrixU();
    u.col(2) *= -1;
    rotation = u * svd.matrixV().transpose();
  }
  return {rotation, translation / double(transforms.size())};
}

}  // namespace

int ArrayCalibration::calibrated_count() const {
  int n = 0;
  for (const auto& c : cameras) n += c.calibrated ? 1 : 0;
  return n;
}

ArrayCalibration CalibrateArray(const std::filesystem::path& dir, const CaptureManifest& manifest,
                                const CalibrationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ArrayCalibration out;
  out.rows = manifest.rows;
  out.cols = manifest.cols;
  out.pitch_mm = manifest.pitch_mm;
  out.width = manifest.sensor_width;
  out.height = manifest.sensor_height;
  if (options.intrinsics_board)
    out.intrinsics_board = *options.intrinsics_board;
  else if (manifest.intrinsics_board)
    out.intrinsics_board = *manifest.intrinsics_board;
  else
    throw UsageError("the session's manifest records no intrinsics board: give --intrinsics-board");
  if (options.world_board)
    out.world_board = *options.world_board;
  else if (manifest.world_board)
    out.world_board = *manifest.world_board;
  else
    throw UsageError("the session's manifest records no world board: give --world-board");
  if (manifest.shots_of(ShotKind::kIntrinsics).empty())
    throw Error(
        fmt::format("{}: the session has no intrinsics shots", (dir / kManifestName).string()));
  if (manifest.shots_of(ShotKind::kWorld).size() != 1)
    throw Error(fmt::format("{}: the session needs exactly one world shot, it has {}",
                            (dir / kManifestName).string(),
                            manifest.shots_of(ShotKind::kWorld).size()));

  // 1. Every board.
  SessionDetections found =
      DetectSessionBoards(dir, manifest, out.intrinsics_board, out.world_board, options.image_done);
  out.detection_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.intrinsics_shots = found.intrinsics_shot_names;
  // A board found nowhere is most likely not the board named: say so, not camera by camera.
  std::size_t intrinsics_found = 0, world_found = 0, intrinsics_images = 0, world_images = 0;
  for (const CameraDetections& d : found.cameras) {
    intrinsics_found += d.intrinsics.size();
    world_found += d.world ? 1 : 0;
  }
  for (const Shot& shot : manifest.shots) {
    if (shot.kind == ShotKind::kIntrinsics) intrinsics_images += shot.images.size();
    if (shot.kind == ShotKind::kWorld) world_images += shot.images.size();
  }
  // A board found nowhere: most likely not the board the flag or manifest names.
  auto found_nowhere = [](const std::string& kind, const BoardSpec& board, std::size_t images) {
    return Error(fmt::format(
        "the {} board {} was found in none of the {} {} images: is that the board in the "
        "photographs? (--{}-board: a chessboard COLSxROWS@MM counts inner corners, a ChArUco "
        "board charuco:SXxSY@SQUARE/MARKER squares)",
        kind, board.spec(), images, kind, kind));
  };
  if (intrinsics_found == 0)
    throw found_nowhere("intrinsics", out.intrinsics_board, intrinsics_images);
  if (world_found == 0) throw found_nowhere("world", out.world_board, world_images);
  const int shots = found.intrinsics_shots;
  out.cameras.resize(found.cameras.size());
  for (std::size_t i = 0; i < found.cameras.size(); ++i) {
    CameraCalibration& c = out.cameras[i];
    const CameraDetections& d = found.cameras[i];
    c.row = d.row;
    c.col = d.col;
    c.warnings = d.warnings;
    c.world_board_found = d.world.has_value();
    for (const BoardView& v : d.intrinsics)
      c.shots_used.push_back(found.intrinsics_shot_names[std::size_t(v.shot)]);
  }
  // Cameras the manifest has no image of.
  for (const Shot& shot : manifest.shots) {
    if (shot.kind == ShotKind::kVideo) continue;  // recordings are not calibration's
    std::vector<bool> present(out.cameras.size(), false);
    for (const ShotImage& image : shot.images)
      present[std::size_t(image.row * out.cols + image.col)] = true;
    for (std::size_t i = 0; i < present.size(); ++i)
      if (!present[i])
        out.cameras[i].warnings.push_back(fmt::format("no image in shot '{}'", shot.name));
  }

  // 2. Each camera alone (the paper's method), in parallel.
  std::vector<std::optional<SingleCameraCalibration>> single(out.cameras.size());
  tbb::parallel_for(std::size_t(0), out.cameras.size(), [&](std::size_t i) {
    CameraCalibration& c = out.cameras[i];
    const CameraDetections& d = found.cameras[i];
    if (int(d.intrinsics.size()) < options.min_views) {
      c.reason = fmt::format(
          "the intrinsics board {} was found in {} of {} intrinsics shots; at least {} are "
          "needed (retake them with the whole board in this camera's view, or give the board "
          "used with --intrinsics-board)",
          out.intrinsics_board.spec(), d.intrinsics.size(), shots, options.min_views);
      return;
    }
    std::vector<std::vector<cv::Point2f>> views;
    for (const BoardView& v : d.intrinsics) views.push_back(v.corners);
    try {
      single[i] = CalibrateSingleCamera(views, out.intrinsics_board, out.width, out.height);
      c.single_intrinsics = single[i]->intrinsics;
      c.single_rms_px = single[i]->rms_px;
      if (d.world) {
        const Rigid3 camera_from_world =
            BoardPose(single[i]->intrinsics, out.world_board, *d.world);
        c.single_center = camera_from_world.inverse().translation;
      }
    } catch (const Error& e) {
      c.reason = fmt::format("its own calibration failed: {}", e.what());
      single[i].reset();
    }
  });

  // Initial board poses in the world, from cameras that saw both the board and the world board.
  out.world_from_board.assign(std::size_t(shots), Rigid3{});
  std::vector<bool> shot_known(std::size_t(shots), false);
  {
    std::vector<std::vector<Rigid3>> estimates(static_cast<std::size_t>(shots));
    for (std::size_t i = 0; i < out.cameras.size(); ++i) {
      if (!single[i] || !found.cameras[i].world) continue;
      const Rigid3 world_from_camera =
          BoardPose(single[i]->intrinsics, out.world_board, *found.cameras[i].world).inverse();
      const auto& views = found.cameras[i].intrinsics;
      for (std::size_t v = 0; v < views.size(); ++v)
        estimates[std::size_t(views[v].shot)].push_back(world_from_camera *
                                                        single[i]->camera_from_board[v]);
    }
    for (int k = 0; k < shots; ++k)
      if (!estimates[std::size_t(k)].empty()) {
        out.world_from_board[std::size_t(k)] = MeanRigid(estimates[std::size_t(k)]);
        shot_known[std::size_t(k)] = true;
      }
  }
  // Initial camera poses: from the world board, else through a shared intrinsics shot.
  std::vector<RigCamera> rig;
  std::vector<std::size_t> rig_index;
  for (std::size_t i = 0; i < out.cameras.size(); ++i) {
    if (!single[i]) continue;
    CameraCalibration& c = out.cameras[i];
    const CameraDetections& d = found.cameras[i];
    RigCamera r;
    r.row = c.row;
    r.col = c.col;
    r.intrinsics = single[i]->intrinsics;
    r.views = &d.intrinsics;
    r.world = &d.world;
    if (d.world) {
      r.camera_from_world = BoardPose(single[i]->intrinsics, out.world_board, *d.world);
    } else {
      std::vector<Rigid3> through_boards;
      for (std::size_t v = 0; v < d.intrinsics.size(); ++v)
        if (shot_known[std::size_t(d.intrinsics[v].shot)])
          through_boards.push_back(
              single[i]->camera_from_board[v] *
              out.world_from_board[std::size_t(d.intrinsics[v].shot)].inverse());
      if (through_boards.empty()) {
        c.reason =
            "it did not find the world board in the world shot, and shares no intrinsics shot "
            "with a camera that did (hold the intrinsics board once where this camera and a "
            "camera that sees the world board both see it whole)";
        continue;
      }
      r.camera_from_world = MeanRigid(through_boards);
    }
    rig.push_back(r);
    rig_index.push_back(i);
  }
  if (rig.size() < 3) {
    // Each camera that failed, with its reason (the first few).
    std::vector<std::string> reasons;
    for (const CameraCalibration& c : out.cameras)
      if (!c.reason.empty() && reasons.size() < 5)
        reasons.push_back(fmt::format("{}: {}", CameraLabel(c.row, c.col), c.reason));
    throw Error(
        fmt::format("{}: only {} of {} cameras could be calibrated; the array needs at least 3{}{}",
                    dir.string(), rig.size(), out.cameras.size(), reasons.empty() ? "" : ":\n  ",
                    fmt::join(reasons, "\n  ")));
  }

  // 3. Joint.
  out.bundle_adjustment = BundleAdjustArray(rig, out.world_from_board, shot_known,
                                            out.intrinsics_board, out.world_board);
  std::vector<GridCamera> joint_centers, single_centers;
  for (std::size_t r = 0; r < rig.size(); ++r) {
    CameraCalibration& c = out.cameras[rig_index[r]];
    c.calibrated = true;
    c.intrinsics = rig[r].intrinsics;
    c.world_from_camera = rig[r].camera_from_world.inverse();
    c.rms_px = rig[r].rms_px;
    c.corners = rig[r].corners;
    if (c.rms_px > 1.0)
      c.warnings.push_back(fmt::format(
          "reprojection RMS {:.2f} px is high: check its images for blur or a moved module",
          c.rms_px));
    joint_centers.push_back({c.row, c.col, c.world_from_camera.translation});
    if (c.single_center) single_centers.push_back({c.row, c.col, *c.single_center});
  }

  // A world board hung the other way up numbers its corners from its other end: the world
  // frame (the board's) is then turned half a turn against the array. Seen from the array, the
  // board's bottom-left corner is the world's origin, so turn the frame back about the board's
  // centre; a grid turned a quarter turn or mirrored against the board is refused.
  const GridOrientation orientation = GridAgainstBoard(joint_centers);
  if (orientation.turn == GridTurn::kHalfTurn) {
    out.world_board_turned = true;
    const Rigid3 turn{Eigen::AngleAxisd(M_PI, Vec3::UnitZ()).toRotationMatrix(),
                      Vec3(out.world_board.width_mm(), out.world_board.height_mm(), 0)};
    for (CameraCalibration& c : out.cameras) {
      if (c.calibrated) c.world_from_camera = turn * c.world_from_camera;
      if (c.single_center) c.single_center = turn * *c.single_center;
    }
    for (Rigid3& board : out.world_from_board) board = turn * board;
    for (GridCamera& g : joint_centers) g.center = turn * g.center;
    for (GridCamera& g : single_centers) g.center = turn * g.center;
  } else if (orientation.turn != GridTurn::kAligned) {
    throw Error(fmt::format(
        "the world shot: the camera grid, as the array file numbers it, runs {} against the "
        "world board {} (its columns at {:.0f} degrees to the board's x axis). Either the array "
        "file's rows and columns are not lfcam's (row 0 at the bottom, column 0 at the left, "
        "seen from behind the array), or the board hangs "
        "on its side: hang it with its {} inner corners along the array's rows and shoot the "
        "world shot again",
        orientation.turn == GridTurn::kMirrored ? "mirrored" : "a quarter turn",
        out.world_board.spec(), orientation.angle_deg, out.world_board.cols));
  }

  // 4. The paper's array fit, on the joint centres (and, for comparison, on the single ones).
  const Vec3 board_center(0.5 * out.world_board.width_mm(), 0.5 * out.world_board.height_mm(), 0);
  out.fit = FitArray(joint_centers, out.rows, out.cols, out.pitch_mm, board_center);
  for (std::size_t r = 0; r < joint_centers.size(); ++r) {
    CameraCalibration& c =
        out.cameras[std::size_t(joint_centers[r].row * out.cols + joint_centers[r].col)];
    c.ideal_center = out.fit.ideal_centers[r];
    c.distance_to_ideal_mm = out.fit.distance_to_ideal_mm[r];
  }
  if (single_centers.size() >= 3) {
    try {
      out.single_fit = FitArray(single_centers, out.rows, out.cols, out.pitch_mm, board_center);
    } catch (const Error&) {
      out.single_fit.reset();
    }
  }
  out.slab.uv = out.fit.array;
  out.slab.st = ViewWindow{Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), out.world_board.width_mm(),
                           out.world_board.height_mm()};
  out.slab.st_domain = {};
  out.slab.validate();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

nlohmann::json V3(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

nlohmann::json CalibrationToJson(const ArrayCalibration& a) {
  nlohmann::json cameras = nlohmann::json::array();
  for (const CameraCalibration& c : a.cameras) {
    nlohmann::json j = {{"row", c.row}, {"col", c.col}, {"calibrated", c.calibrated}};
    if (!c.calibrated) j["reason"] = c.reason;
    if (c.calibrated) {
      j["intrinsics"] = IntrinsicsToJson(c.intrinsics);
      j["center"] = V3(c.world_from_camera.translation);
      j["orientation"] = RotationToJson(c.world_from_camera.rotation);
      j["reprojection_rms_px"] = c.rms_px;
      j["corners"] = c.corners;
      j["ideal_center"] = V3(c.ideal_center);
      j["distance_to_ideal_mm"] = c.distance_to_ideal_mm;
    }
    j["shots_used"] = c.shots_used;
    j["world_board_found"] = c.world_board_found;
    j["warnings"] = c.warnings;
    if (c.single_intrinsics) {
      nlohmann::json single = {{"intrinsics", IntrinsicsToJson(*c.single_intrinsics)},
                               {"reprojection_rms_px", c.single_rms_px}};
      if (c.single_center) single["center"] = V3(*c.single_center);
      j["single_camera"] = single;
    }
    cameras.push_back(j);
  }
  auto fit_json = [](const ArrayFit& f) {
    return nlohmann::json{{"plane_normal", V3(f.plane_normal)},
                          {"barycentre", V3(f.barycentre)},
                          {"plane_rms_mm", f.plane_rms_mm},
                          {"alpha_mm", f.alpha},
                          {"beta_mm", f.beta},
                          {"theta_rad", f.theta_newton},
                          {"theta_closed_form_rad", f.theta_closed},
                          {"newton_iterations", f.newton_iterations},
                          {"grid_rms_mm", f.grid_rms_mm},
                          {"p_ca", V3(f.array.p_ca)},
                          {"u_ca", V3(f.array.u_ca)},
                          {"v_ca", V3(f.array.v_ca)},
                          {"n_ca", V3(f.array.n_ca)}};
  };
  nlohmann::json slab;
  to_json(slab, a.slab);
  nlohmann::json boards = nlohmann::json::array();
  for (std::size_t k = 0; k < a.world_from_board.size(); ++k)
    boards.push_back({{"shot", a.intrinsics_shots[k]},
                      {"world_from_board",
                       {{"rotation", RotationToJson(a.world_from_board[k].rotation)},
                        {"translation", V3(a.world_from_board[k].translation)}}}});
  const auto& ba = a.bundle_adjustment;
  nlohmann::json j = {
      {"format", "lfcam-calibration"},
      {"version", kCalibrationVersion},
      {"grid", {{"rows", a.rows}, {"cols", a.cols}, {"pitch_mm", a.pitch_mm}}},
      {"sensor", {{"width", a.width}, {"height", a.height}}},
      {"boards",
       {{"intrinsics", BoardToJson(a.intrinsics_board)}, {"world", BoardToJson(a.world_board)}}},
      {"slab", slab},
      {"array_fit", fit_json(a.fit)},
      {"world_board_turned", a.world_board_turned},
      {"bundle_adjustment",
       {{"residual_blocks", ba.residual_blocks},
        {"parameters", ba.parameters},
        {"iterations", ba.iterations},
        {"initial_rms_px", ba.initial_rms_px},
        {"final_rms_px", ba.final_rms_px},
        {"converged", ba.converged},
        {"seconds", ba.seconds},
        {"summary", ba.summary}}},
      {"board_poses", boards},
      {"calibrated_cameras", a.calibrated_count()},
      {"seconds", a.seconds},
      {"cameras", cameras}};
  if (a.single_fit) j["single_camera_array_fit"] = fit_json(*a.single_fit);
  return j;
}

}  // namespace lfcam
