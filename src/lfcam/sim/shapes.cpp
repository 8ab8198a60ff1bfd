#include "lfcam/sim/shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lfcam {

RectangleShape::RectangleShape(const Vec3& center, const Vec3& axis_u, const Vec3& axis_v,
                               double half_u, double half_v)
    : center_(center),
      axis_u_(axis_u.normalized()),
      axis_v_(axis_v.normalized()),
      normal_(axis_u.cross(axis_v).normalized()),
      half_u_(half_u),
      half_v_(half_v) {}

bool RectangleShape::Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const {
  const double denom = normal_.dot(ray.direction);
  if (std::abs(denom) < 1e-12) return false;
  const double t = normal_.dot(center_ - ray.origin) / denom;
  if (t <= t_min || t >= t_max) return false;
  const Vec3 d = ray.at(t) - center_;
  const double a = d.dot(axis_u_), b = d.dot(axis_v_);
  if (std::abs(a) > half_u_ || std::abs(b) > half_v_) return false;
  *hit = {t, normal_, Vec2(a + half_u_, b + half_v_)};
  return true;
}

BoxShape::BoxShape(const Vec3& min_corner, const Vec3& max_corner)
    : min_(min_corner.cwiseMin(max_corner)), max_(min_corner.cwiseMax(max_corner)) {}

bool BoxShape::Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const {
  double t0 = t_min, t1 = t_max;
  int axis_in = -1, axis_out = -1;
  for (int a = 0; a < 3; ++a) {
    const double inv = 1.0 / ray.direction[a];
    double ta = (min_[a] - ray.origin[a]) * inv, tb = (max_[a] - ray.origin[a]) * inv;
    if (ta > tb) std::swap(ta, tb);
    if (ta > t0) t0 = ta, axis_in = a;
    if (tb < t1) t1 = tb, axis_out = a;
    if (t0 > t1) return false;
  }
  // Entering hit, or (from inside) the exit.
  double t = t0;
  int axis = axis_in;
  if (axis_in < 0) t = t1, axis = axis_out;
  if (axis < 0 || t <= t_min || t >= t_max) return false;
  Vec3 n = Vec3::Zero();
  n[axis] = ray.direction[axis] > 0 ? -1.0 : 1.0;
  const Vec3 p = ray.at(t);
  // Faces map with x (or z on the x faces) across and y up where possible.
  const int across = axis == 0 ? 2 : 0;
  const int up = axis == 1 ? 2 : 1;
  *hit = {t, n, Vec2(p[across] - min_[across], p[up] - min_[up])};
  return true;
}

SphereShape::SphereShape(const Vec3& center, double radius) : center_(center), radius_(radius) {}

bool SphereShape::Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const {
  const Vec3 oc = ray.origin - center_;
  const double a = ray.direction.squaredNorm();
  const double half_b = oc.dot(ray.direction);
  const double c = oc.squaredNorm() - radius_ * radius_;
  const double disc = half_b * half_b - a * c;
  if (disc < 0) return false;
  const double sq = std::sqrt(disc);
  double t = (-half_b - sq) / a;
  if (t <= t_min || t >= t_max) {
    t = (-half_b + sq) / a;
    if (t <= t_min || t >= t_max) return false;
  }
  const Vec3 n = (ray.at(t) - center_) / radius_;
  const double longitude = std::atan2(n.x(), n.z());
  const double latitude = std::asin(std::clamp(n.y(), -1.0, 1.0));
  *hit = {t, n, Vec2(longitude * radius_, latitude * radius_)};
  return true;
}

ConeShape::ConeShape(const Vec3& base_center, double radius, double height)
    : base_(base_center), radius_(radius), height_(height) {}

bool ConeShape::Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const {
  bool found = false;
  // Lateral surface: (x^2 + z^2) = (k (h - y))^2 with k = r / h, 0 <= y <= h (local frame).
  const Vec3 o = ray.origin - base_;
  const Vec3& d = ray.direction;
  const double k = radius_ / height_, k2 = k * k;
  const double a = d.x() * d.x() + d.z() * d.z() - k2 * d.y() * d.y();
  const double b = 2 * (o.x() * d.x() + o.z() * d.z() + k2 * (height_ - o.y()) * d.y());
  const double c = o.x() * o.x() + o.z() * o.z() - k2 * (height_ - o.y()) * (height_ - o.y());
  const double disc = b * b - 4 * a * c;
  if (std::abs(a) > 1e-12 && disc >= 0) {
    const double sq = std::sqrt(disc);
    for (const double t : {(-b - sq) / (2 * a), (-b + sq) / (2 * a)}) {
      if (t <= t_min || t >= t_max || (found && t >= hit->t)) continue;
      const Vec3 p = o + t * d;
      if (p.y() < 0 || p.y() > height_) continue;
      const double r = std::hypot(p.x(), p.z());
      const Vec3 n = Vec3(p.x(), r * k, p.z()).normalized();
      const double angle = std::atan2(p.x(), p.z());
      *hit = {t, n, Vec2(angle * radius_, p.y())};
      found = true;
    }
  }
  // Base disc at y = 0.
  if (std::abs(d.y()) > 1e-12) {
    const double t = -o.y() / d.y();
    const Vec3 p = o + t * d;
    if (t > t_min && t < t_max && (!found || t < hit->t) &&
        p.x() * p.x() + p.z() * p.z() <= radius_ * radius_) {
      *hit = {t, Vec3(0, -1, 0), Vec2(p.x(), p.z())};
      found = true;
    }
  }
  return found;
}

DiscShape::DiscShape(const Vec3& center, const Vec3& normal, double radius)
    : center_(center), normal_(normal.normalized()), radius_(radius) {
  const Vec3 helper = std::abs(normal_.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitX();
  axis_u_ = helper.cross(normal_).normalized();
  axis_v_ = normal_.cross(axis_u_);
}

bool DiscShape::Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const {
  const double denom = normal_.dot(ray.direction);
  if (std::abs(denom) < 1e-12) return false;
  const double t = normal_.dot(center_ - ray.origin) / denom;
  if (t <= t_min || t >= t_max) return false;
  const Vec3 d = ray.at(t) - center_;
  if (d.squaredNorm() > radius_ * radius_) return false;
  *hit = {t, normal_, Vec2(d.dot(axis_u_), d.dot(axis_v_))};
  return true;
}

BoundingSphere RectangleShape::Bounds() const { return {center_, std::hypot(half_u_, half_v_)}; }

BoundingSphere BoxShape::Bounds() const { return {(min_ + max_) / 2, (max_ - min_).norm() / 2}; }

BoundingSphere SphereShape::Bounds() const { return {center_, radius_}; }

BoundingSphere ConeShape::Bounds() const {
  // The sphere through the base's rim whose centre is on the axis, or the base's own when the
  // apex falls inside that.
  const double y = std::max(0.0, (height_ * height_ - radius_ * radius_) / (2 * height_));
  return {base_ + Vec3(0, y, 0), std::hypot(radius_, y)};
}

BoundingSphere DiscShape::Bounds() const { return {center_, radius_}; }

}  // namespace lfcam
