#pragma once
// Small value types shared by every stage: vectors, rays, planes and rigid transforms.
// All lengths are millimetres in the world frame unless a name says otherwise.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

namespace lfcam {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

struct Ray {
  Vec3 origin;
  Vec3 direction;  // not necessarily unit length
  Vec3 at(double t) const { return origin + t * direction; }
};

// The plane {x : normal . (x - point) = 0}.
struct Plane {
  Vec3 point;
  Vec3 normal;  // unit length

  // Parameter t along the (infinite) line of `ray` where it meets the plane; nullopt when the
  // ray runs parallel to it.
  std::optional<double> intersect(const Ray& ray) const {
    const double denom = normal.dot(ray.direction);
    if (std::abs(denom) < 1e-12) return std::nullopt;
    return normal.dot(point - ray.origin) / denom;
  }
  double signed_distance(const Vec3& x) const { return normal.dot(x - point); }
};

// A rigid motion named by its frames, COLMAP-style: `world_from_camera * x_camera = x_world`.
struct Rigid3 {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();

  Vec3 operator*(const Vec3& x) const { return rotation * x + translation; }
  Rigid3 operator*(const Rigid3& other) const {
    return {rotation * other.rotation, rotation * other.translation + translation};
  }
  Rigid3 inverse() const {
    const Mat3 rt = rotation.transpose();
    return {rt, -(rt * translation)};
  }
};

}  // namespace lfcam
