#include "lfcam/sim/motion.h"

#include <Eigen/Geometry>

namespace lfcam {

Rigid3 Motion::At(double t_seconds) const {
  Rigid3 spin;
  if (spin_rad_per_s != 0.0) {
    spin.rotation = Eigen::AngleAxisd(spin_rad_per_s * t_seconds, axis.normalized()).matrix();
    spin.translation = pivot - spin.rotation * pivot;  // the pivot stays put
  }
  Rigid3 move;
  move.translation = velocity_mm_per_s * t_seconds;
  return move * spin;
}

MovedShape::MovedShape(std::shared_ptr<const Shape> base, const Rigid3& world_from_object)
    : base_(std::move(base)),
      world_from_object_(world_from_object),
      object_from_world_(world_from_object.inverse()) {}

bool MovedShape::Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const {
  const Ray local{object_from_world_ * ray.origin, object_from_world_.rotation * ray.direction};
  if (!base_->Intersect(local, t_min, t_max, hit)) return false;
  hit->normal = world_from_object_.rotation * hit->normal;
  return true;
}

BoundingSphere MovedShape::Bounds() const {
  const BoundingSphere b = base_->Bounds();
  return {world_from_object_ * b.center, b.radius};
}

}  // namespace lfcam
