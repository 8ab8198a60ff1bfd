#pragma once
// Motion in the simulator's scenes (issue 24: light field video): a rigid motion over time, a
// spin about an axis through a pivot at a constant rate and a translation at a constant velocity,
// and the shape it moves. Time t is in seconds from the recording's start; t = 0 is where the
// scene's own layout puts every object.
#include <memory>

#include "lfcam/core/geometry.h"
#include "lfcam/sim/shapes.h"

namespace lfcam {

struct Motion {
  Vec3 velocity_mm_per_s = Vec3::Zero();
  Vec3 pivot = Vec3::Zero();    // world mm: a point on the spin's axis
  Vec3 axis = Vec3::UnitZ();    // the spin's axis (unit), right-handed
  double spin_rad_per_s = 0.0;  // positive: counter-clockwise looking down the axis

  // world_from_object at time t: the object's layout (its frame at t = 0) spun about the axis
  // through the pivot by spin * t, then moved by velocity * t.
  Rigid3 At(double t_seconds) const;
  // Where a point of the object (at p at t = 0) is at time t.
  Vec3 PointAt(const Vec3& p, double t_seconds) const { return At(t_seconds) * p; }
};

// A shape moved rigidly: `base` as laid out, placed by world_from_object. Distances along a ray
// are unchanged, and texture coordinates move with the surface.
class MovedShape final : public Shape {
 public:
  MovedShape(std::shared_ptr<const Shape> base, const Rigid3& world_from_object);
  bool Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const override;
  BoundingSphere Bounds() const override;

 private:
  std::shared_ptr<const Shape> base_;
  Rigid3 world_from_object_, object_from_world_;
};

}  // namespace lfcam
