#include "lfcam/calib/bundle_adjustment.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "lfcam/calib/board_detection.h"
#include "lfcam/core/error.h"

namespace lfcam {
namespace {

// A camera's parameter block: camera_from_world as angle-axis and translation, then fx, fy, cx,
// cy, k1, k2, p1, p2, k3. One block per camera, so that Ceres can eliminate the cameras (no
// residual touches two) and solve a small system in the board poses.
constexpr int kCameraBlock = 15;
// A board's: world_from_board as angle-axis and translation.
constexpr int kBoardBlock = 6;

struct CornerResidual {
  double board_x, board_y, pixel_x, pixel_y;

  template <typename T>
  bool operator()(const T* camera, const T* board, T* residual) const {
    const T on_board[3] = {T(board_x), T(board_y), T(0)};
    T world[3];
    ceres::AngleAxisRotatePoint(board, on_board, world);
    for (int i = 0; i < 3; ++i) world[i] += board[3 + i];
    T p[3];
    ceres::AngleAxisRotatePoint(camera, world, p);
    for (int i = 0; i < 3; ++i) p[i] += camera[3 + i];
    const T x = p[0] / p[2], y = p[1] / p[2];
    const T& fx = camera[6];
    const T& fy = camera[7];
    const T& cx = camera[8];
    const T& cy = camera[9];
    const T& k1 = camera[10];
    const T& k2 = camera[11];
    const T& p1 = camera[12];
    const T& p2 = camera[13];
    const T& k3 = camera[14];
    const T r2 = x * x + y * y;
    const T radial = T(1) + r2 * (k1 + r2 * (k2 + r2 * k3));
    const T xd = x * radial + T(2) * p1 * x * y + p2 * (r2 + T(2) * x * x);
    const T yd = y * radial + p1 * (r2 + T(2) * y * y) + T(2) * p2 * x * y;
    residual[0] = fx * xd + cx - T(pixel_x);
    residual[1] = fy * yd + cy - T(pixel_y);
    return true;
  }
};

std::array<double, kCameraBlock> PackCamera(const RigCamera& c) {
  std::array<double, kCameraBlock> b{};
  const Vec3 aa = AngleAxisFromRotation(c.camera_from_world.rotation);
  for (int i = 0; i < 3; ++i) {
    b[std::size_t(i)] = aa[i];
    b[std::size_t(3 + i)] = c.camera_from_world.translation[i];
  }
  const auto& k = c.intrinsics;
  const auto d = k.distortion;
  const double rest[] = {k.fx, k.fy, k.cx, k.cy, d.k1, d.k2, d.p1, d.p2, d.k3};
  for (int i = 0; i < 9; ++i) b[std::size_t(6 + i)] = rest[i];
  return b;
}

void UnpackCamera(const std::array<double, kCameraBlock>& b, RigCamera& c) {
  c.camera_from_world.rotation = RotationFromAngleAxis(Vec3(b[0], b[1], b[2]));
  c.camera_from_world.translation = Vec3(b[3], b[4], b[5]);
  auto& k = c.intrinsics;
  k.fx = b[6];
  k.fy = b[7];
  k.cx = b[8];
  k.cy = b[9];
  k.distortion = {b[10], b[11], b[12], b[13], b[14]};
}

std::array<double, kBoardBlock> PackRigid(const Rigid3& t) {
  const Vec3 aa = AngleAxisFromRotation(t.rotation);
  return {aa.x(), aa.y(), aa.z(), t.translation.x(), t.translation.y(), t.translation.z()};
}

Rigid3 UnpackRigid(const std::array<double, kBoardBlock>& b) {
  return {RotationFromAngleAxis(Vec3(b[0], b[1], b[2])), Vec3(b[3], b[4], b[5])};
}

// The sum of squared reprojection errors over the corners found, and their number.
struct SquaredError {
  double sum = 0;
  int count = 0;
};

SquaredError Reprojection(const CameraIntrinsics& intrinsics, const Rigid3& camera_from_board,
                          const std::vector<Vec3>& points,
                          const std::vector<cv::Point2f>& corners) {
  SquaredError e;
  for (std::size_t i = 0; i < points.size() && i < corners.size(); ++i) {
    if (!CornerFound(corners[i])) continue;
    const auto p = intrinsics.Project(camera_from_board * points[i]);
    e.sum += p ? (*p - Vec2(corners[i].x, corners[i].y)).squaredNorm()
               : std::numeric_limits<double>::infinity();
    ++e.count;
  }
  return e;
}

}  // namespace

double ReprojectionRms(const CameraIntrinsics& intrinsics, const Rigid3& camera_from_board,
                       const std::vector<Vec3>& points, const std::vector<cv::Point2f>& corners) {
  const SquaredError e = Reprojection(intrinsics, camera_from_board, points, corners);
  return std::sqrt(e.sum / std::max(1, e.count));
}

BundleAdjustmentReport BundleAdjustArray(std::vector<RigCamera>& cameras,
                                         std::vector<Rigid3>& world_from_board,
                                         const std::vector<bool>& shot_known,
                                         const BoardSpec& intrinsics_board,
                                         const BoardSpec& world_board,
                                         const BundleAdjustmentOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::array<double, kCameraBlock>> camera_blocks;
  for (const auto& c : cameras) camera_blocks.push_back(PackCamera(c));
  std::vector<std::array<double, kBoardBlock>> board_blocks;
  for (const auto& t : world_from_board) board_blocks.push_back(PackRigid(t));
  std::array<double, kBoardBlock> world_block{};  // the world board: the identity, held

  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::HuberLoss loss(options.huber_px);
  const auto intrinsics_points = intrinsics_board.corners();
  const auto world_points = world_board.corners();
  BundleAdjustmentReport report;
  auto add = [&](double* camera, double* board, const Vec3& point, const cv::Point2f& pixel) {
    if (!CornerFound(pixel)) return;  // not in a partial ChArUco view
    auto* cost = new ceres::AutoDiffCostFunction<CornerResidual, 2, kCameraBlock, kBoardBlock>(
        new CornerResidual{point.x(), point.y(), pixel.x, pixel.y});
    problem.AddResidualBlock(cost, &loss, camera, board);
    ++report.residual_blocks;
  };
  bool world_used = false;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    double* camera = camera_blocks[i].data();
    for (const BoardView& view : *cameras[i].views) {
      if (!shot_known[std::size_t(view.shot)]) continue;
      for (std::size_t p = 0; p < intrinsics_points.size(); ++p)
        add(camera, board_blocks[std::size_t(view.shot)].data(), intrinsics_points[p],
            view.corners[p]);
    }
    if (cameras[i].world && *cameras[i].world) {
      for (std::size_t p = 0; p < world_points.size(); ++p)
        add(camera, world_block.data(), world_points[p], (**cameras[i].world)[p]);
      world_used = true;
    }
  }
  if (!world_used)
    throw Error(
        "no camera found the world board in the world shot: the array cannot be placed (hang "
        "the board flat where the cameras see all of it, evenly lit, and give its size with "
        "--world-board)");
  problem.SetParameterBlockConstant(world_block.data());
  // Keep the principal points and focal lengths physical.
  for (auto& b : camera_blocks) {
    problem.SetParameterLowerBound(b.data(), 6, 0.2 * b[6]);
    problem.SetParameterLowerBound(b.data(), 7, 0.2 * b[7]);
  }

  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (auto& b : camera_blocks) ordering->AddElementToGroup(b.data(), 0);
  for (std::size_t k = 0; k < board_blocks.size(); ++k)
    if (shot_known[k] && problem.HasParameterBlock(board_blocks[k].data()))
      ordering->AddElementToGroup(board_blocks[k].data(), 1);
  ordering->AddElementToGroup(world_block.data(), 1);

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_SCHUR;
  solver.linear_solver_ordering = ordering;
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = options.threads > 0 ? options.threads
                                           : int(std::max(1u, std::thread::hardware_concurrency()));
  solver.function_tolerance = 1e-10;
  solver.parameter_tolerance = 1e-10;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  report.parameters = summary.num_parameters;
  report.iterations = int(summary.iterations.size());
  report.converged = summary.termination_type == ceres::CONVERGENCE;
  report.summary = summary.BriefReport();
  report.initial_rms_px = std::sqrt(2 * summary.initial_cost / std::max(1, report.residual_blocks));
  if (!summary.IsSolutionUsable())
    throw Error(fmt::format("the array bundle adjustment failed: {}", summary.BriefReport()));

  for (std::size_t i = 0; i < cameras.size(); ++i) UnpackCamera(camera_blocks[i], cameras[i]);
  for (std::size_t k = 0; k < board_blocks.size(); ++k)
    if (shot_known[k]) world_from_board[k] = UnpackRigid(board_blocks[k]);
  // Plain (not robust) reprojection RMS, per camera and overall.
  double total = 0;
  int total_corners = 0;
  for (auto& c : cameras) {
    double sum = 0;
    int n = 0;
    for (const BoardView& view : *c.views) {
      if (!shot_known[std::size_t(view.shot)]) continue;
      const SquaredError e =
          Reprojection(c.intrinsics, c.camera_from_world * world_from_board[std::size_t(view.shot)],
                       intrinsics_points, view.corners);
      sum += e.sum;
      n += e.count;
    }
    if (c.world && *c.world) {
      const SquaredError e =
          Reprojection(c.intrinsics, c.camera_from_world, world_points, **c.world);
      sum += e.sum;
      n += e.count;
    }
    c.rms_px = n ? std::sqrt(sum / n) : 0;
    c.corners = n;
    total += sum;
    total_corners += n;
  }
  report.final_rms_px = total_corners ? std::sqrt(total / total_corners) : 0;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace lfcam
