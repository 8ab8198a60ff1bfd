#include "lfcam/core/camera_model.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"

namespace lfcam {

Vec2 Distortion::Apply(const Vec2& p) const {
  const double x = p.x(), y = p.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
          y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
}

std::optional<Vec2> Distortion::Remove(const Vec2& distorted) const {
  if (is_zero()) return distorted;
  // Newton's method on Apply(p) = distorted, starting from the distorted point.
  Vec2 p = distorted;
  for (int iteration = 0; iteration < 20; ++iteration) {
    const Vec2 residual = Apply(p) - distorted;
    if (residual.squaredNorm() < 1e-26) return p;
    const double x = p.x(), y = p.y();
    const double r2 = x * x + y * y;
    const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double dradial = k1 + r2 * (2 * k2 + 3 * r2 * k3);  // d radial / d r2
    Eigen::Matrix2d J;
    J(0, 0) = radial + 2 * x * x * dradial + 2 * p1 * y + 6 * p2 * x;
    J(0, 1) = 2 * x * y * dradial + 2 * p1 * x + 2 * p2 * y;
    J(1, 0) = 2 * x * y * dradial + 2 * p1 * x + 2 * p2 * y;
    J(1, 1) = radial + 2 * y * y * dradial + 6 * p1 * y + 2 * p2 * x;
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-9)) return std::nullopt;
    p -= J.inverse() * residual;
    if (!p.allFinite() || p.squaredNorm() > 1e6) return std::nullopt;
  }
  if ((Apply(p) - distorted).squaredNorm() < 1e-18) return p;
  return std::nullopt;
}

Mat3 CameraIntrinsics::K() const {
  Mat3 k = Mat3::Identity();
  k(0, 0) = fx;
  k(1, 1) = fy;
  k(0, 2) = cx;
  k(1, 2) = cy;
  return k;
}

std::optional<Vec2> CameraIntrinsics::Project(const Vec3& q) const {
  if (!(q.z() > 0)) return std::nullopt;
  const Vec2 d = distortion.Apply({q.x() / q.z(), q.y() / q.z()});
  return Vec2(fx * d.x() + cx, fy * d.y() + cy);
}

std::optional<Vec3> CameraIntrinsics::Unproject(const Vec2& pixel) const {
  const auto n = distortion.Remove({(pixel.x() - cx) / fx, (pixel.y() - cy) / fy});
  if (!n) return std::nullopt;
  return Vec3(n->x(), n->y(), 1.0);
}

Mat3 WorldFromCameraRotation(const Vec3& u_ca, const Vec3& v_ca, const Vec3& n_ca) {
  Mat3 r;
  r.col(0) = u_ca;   // camera x: right
  r.col(1) = -v_ca;  // camera y: down
  r.col(2) = -n_ca;  // camera z: forward, toward the scene
  return r;
}

Mat3 RotationFromAngleAxis(const Vec3& angle_axis) {
  const double angle = angle_axis.norm();
  if (angle < 1e-300) return Mat3::Identity();
  return Eigen::AngleAxisd(angle, angle_axis / angle).toRotationMatrix();
}

Vec3 AngleAxisFromRotation(const Mat3& rotation) {
  const Eigen::AngleAxisd aa(rotation);
  return aa.angle() * aa.axis();
}

nlohmann::json IntrinsicsToJson(const CameraIntrinsics& c) {
  const auto d = c.distortion.opencv();
  return {{"width", c.width},
          {"height", c.height},
          {"fx", c.fx},
          {"fy", c.fy},
          {"cx", c.cx},
          {"cy", c.cy},
          {"distortion", nlohmann::json(std::vector<double>(d.begin(), d.end()))}};
}

CameraIntrinsics IntrinsicsFromJson(const nlohmann::json& j, const std::string& where) {
  CameraIntrinsics c;
  c.width = int(JsonInteger(j, "width", 1, kMaxImageSide, where));
  c.height = int(JsonInteger(j, "height", 1, kMaxImageSide, where));
  c.fx = JsonNumber(j, "fx", where);
  c.fy = JsonNumber(j, "fy", where);
  c.cx = JsonNumber(j, "cx", where);
  c.cy = JsonNumber(j, "cy", where);
  if (!(c.fx > 0) || !(c.fy > 0) || c.fx > 1e7 || c.fy > 1e7)
    throw Error(fmt::format("{}: focal lengths fx = {}, fy = {} must be positive pixels", where,
                            c.fx, c.fy));
  if (std::abs(c.cx) > 1e6 || std::abs(c.cy) > 1e6)
    throw Error(
        fmt::format("{}: principal point ({}, {}) is far outside the image", where, c.cx, c.cy));
  const auto& d = JsonField(j, "distortion", where);
  if (!d.is_array() || d.size() != 5)
    throw Error(fmt::format("{}: distortion must be [k1, k2, p1, p2, k3]", where));
  const std::string dw = where + ": distortion";
  double k[5];
  for (int i = 0; i < 5; ++i) {
    k[i] = JsonNumber(d[i], "", dw);
    if (std::abs(k[i]) > 1e4) throw Error(fmt::format("{}: coefficient {} is too large", dw, k[i]));
  }
  c.distortion = {k[0], k[1], k[2], k[3], k[4]};
  return c;
}

nlohmann::json RotationToJson(const Mat3& r) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) rows.push_back({r(i, 0), r(i, 1), r(i, 2)});
  return rows;
}

Mat3 RotationFromJson(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3)
    throw Error(fmt::format("{}: a rotation must be 3 rows of 3 numbers", where));
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_array() || j[i].size() != 3)
      throw Error(fmt::format("{}: a rotation must be 3 rows of 3 numbers", where));
    for (int k = 0; k < 3; ++k) r(i, k) = JsonNumber(j[i][k], "", where);
  }
  if (!((r * r.transpose() - Mat3::Identity()).norm() < 1e-6) || !(r.determinant() > 0))
    throw Error(fmt::format("{}: not a rotation (it must be orthonormal, determinant +1)", where));
  return r;
}

}  // namespace lfcam
