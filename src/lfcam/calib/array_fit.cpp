#include "lfcam/calib/array_fit.h"

#include <fmt/format.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "lfcam/core/error.h"
#include "lfcam/core/least_squares.h"

namespace lfcam {

ArrayFit FitArray(const std::vector<GridCamera>& cameras, int rows, int cols, double pitch,
                  const Vec3& scene_side) {
  const std::size_t n = cameras.size();
  if (n < 3)
    throw Error(fmt::format("the array fit needs at least 3 calibrated cameras, got {}", n));
  ArrayFit fit;
  Vec3 mean = Vec3::Zero();
  for (const auto& c : cameras) mean += c.center;
  mean /= double(n);
  fit.barycentre = mean;
  // Total least squares: the plane's normal is the covariance's weakest direction.
  Mat3 covariance = Mat3::Zero();
  for (const auto& c : cameras) covariance += (c.center - mean) * (c.center - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(covariance);
  const Eigen::Vector3d values = eigen.eigenvalues();  // ascending
  if (!(values(1) > 1e-6 * std::max(values(2), 1e-300)) || !(values(1) > 1e-12))
    throw Error(fmt::format(
        "the {} camera centres lie on a line, not a plane (spreads {:.3g} and {:.3g} mm): the "
        "array cannot be fitted",
        n, std::sqrt(values(2) / double(n)), std::sqrt(values(1) / double(n))));
  Vec3 normal = eigen.eigenvectors().col(0).normalized();
  if (normal.dot(mean - scene_side) < 0) normal = -normal;  // away from the scene
  fit.plane_normal = normal;
  fit.plane_rms_mm = std::sqrt(std::max(0.0, values(0)) / double(n));

  // The 2D frame: x is the world x axis projected onto the plane, y = n x x.
  Vec3 e1 = Vec3::UnitX() - normal * normal.x();
  if (e1.norm() < 1e-6) e1 = Vec3::UnitY() - normal * normal.y();
  e1.normalize();
  const Vec3 e2 = normal.cross(e1);

  // Projected centres in the frame; ideal cells centred at the origin.
  std::vector<Vec2> q(n), p(n);
  Vec2 q_mean = Vec2::Zero(), p_mean = Vec2::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = cameras[i].center - mean;
    q[i] = Vec2(d.dot(e1), d.dot(e2));
    p[i] = Vec2(pitch * (cameras[i].col - 0.5 * (cols - 1)),
                pitch * (cameras[i].row - 0.5 * (rows - 1)));
    q_mean += q[i];
    p_mean += p[i];
  }
  q_mean /= double(n);
  p_mean /= double(n);
  double C = 0, S = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = q[i] - q_mean, b = p[i] - p_mean;
    C += a.x() * b.x() + a.y() * b.y();
    S += a.y() * b.x() - a.x() * b.y();
  }
  fit.theta_closed = std::atan2(S, C);
  // Newton-Raphson on f(theta) = S cos - C sin from theta = 0, as the paper does.
  double theta = 0;
  for (fit.newton_iterations = 0; fit.newton_iterations < 50; ++fit.newton_iterations) {
    const double f = S * std::cos(theta) - C * std::sin(theta);
    const double df = -S * std::sin(theta) - C * std::cos(theta);
    if (std::abs(df) < 1e-300) break;
    const double step = f / df;
    theta -= step;
    if (std::abs(step) < 1e-15) break;
  }
  fit.theta_newton = theta;
  if (std::abs(std::remainder(theta - fit.theta_closed, 2 * M_PI)) > 1e-9)
    throw Error(fmt::format(
        "the array fit's Newton-Raphson angle {:.4f} rad disagrees with the closed form {:.4f} "
        "rad: the camera grid, as numbered, is turned by {:.0f} degrees against the world "
        "board's axes (check the array file's rows and columns: row 0 at the bottom, column 0 "
        "at the left, seen from behind the array)",
        theta, fit.theta_closed, fit.theta_closed * 180 / M_PI));
  const Eigen::Rotation2Dd rotation(theta);
  const Vec2 offset = q_mean - rotation * p_mean;  // (alpha*, beta*)
  fit.alpha = offset.x();
  fit.beta = offset.y();

  ArrayPlane& a = fit.array;
  a.rows = rows;
  a.cols = cols;
  a.pitch_mm = pitch;
  const Vec2 u2 = rotation * Vec2::UnitX(), v2 = rotation * Vec2::UnitY();
  a.u_ca = (u2.x() * e1 + u2.y() * e2).normalized();
  a.v_ca = (v2.x() * e1 + v2.y() * e2).normalized();
  a.n_ca = a.u_ca.cross(a.v_ca).normalized();
  const Vec3 grid_center = mean + fit.alpha * e1 + fit.beta * e2;
  a.p_ca = grid_center - 0.5 * a.width_mm() * a.u_ca - 0.5 * a.height_mm() * a.v_ca;

  double sum2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 ideal = a.camera_center(cameras[i].row, cameras[i].col);
    fit.ideal_centers.push_back(ideal);
    const Vec3 projected = cameras[i].center - normal * normal.dot(cameras[i].center - mean);
    sum2 += (projected - ideal).squaredNorm();
    fit.distance_to_ideal_mm.push_back((cameras[i].center - ideal).norm());
  }
  fit.grid_rms_mm = std::sqrt(sum2 / double(n));
  return fit;
}

GridOrientation GridAgainstBoard(const std::vector<GridCamera>& cameras) {
  GridOrientation o;
  const auto n = Eigen::Index(cameras.size());
  Eigen::MatrixXd design(n, 3);
  Eigen::MatrixXd centers(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    design.row(i) << 1.0, cameras[std::size_t(i)].col, cameras[std::size_t(i)].row;
    centers.row(i) = cameras[std::size_t(i)].center.transpose();
  }
  const bool have_cols = n > 1 && design.col(1).maxCoeff() > design.col(1).minCoeff();
  const bool have_rows = n > 1 && design.col(2).maxCoeff() > design.col(2).minCoeff();
  if (!have_cols && !have_rows) return o;
  Eigen::MatrixXd columns(n, 1 + int(have_cols) + int(have_rows));
  columns.col(0) = design.col(0);
  if (have_cols) columns.col(1) = design.col(1);
  if (have_rows) columns.col(columns.cols() - 1) = design.col(2);
  const Eigen::MatrixXd coef = SolveLeastSquares(columns, centers);
  // The columns' direction in the board's plane; from the rows' (a quarter turn back) when the
  // grid is a single column.
  const Vec2 u = have_cols ? Vec2(coef(1, 0), coef(1, 1)) : Vec2::Zero();
  const Vec2 v =
      have_rows ? Vec2(coef(columns.cols() - 1, 0), coef(columns.cols() - 1, 1)) : Vec2::Zero();
  const double angle = have_cols ? std::atan2(u.y(), u.x()) : std::atan2(-v.x(), v.y());
  o.angle_deg = angle * 180 / M_PI;
  if (have_cols && have_rows && u.x() * v.y() - u.y() * v.x() < 0) {
    o.turn = GridTurn::kMirrored;
  } else if (std::abs(o.angle_deg) <= 45) {
    o.turn = GridTurn::kAligned;
  } else if (std::abs(o.angle_deg) >= 135) {
    o.turn = GridTurn::kHalfTurn;
  } else {
    o.turn = GridTurn::kQuarterTurn;
  }
  return o;
}

}  // namespace lfcam
