#pragma once
// Analytic primitives for the ray caster: rectangles, axis-aligned boxes, spheres, upright
// cones and discs. Each reports the hit distance, the normal and millimetre texture coordinates.
#include <memory>

#include "lfcam/core/geometry.h"

namespace lfcam {

struct SurfaceHit {
  double t = 0;
  Vec3 normal;  // unit, not yet flipped toward the viewer
  Vec2 uv_mm;   // texture coordinates on the surface
};

// A sphere that holds a whole shape: where a ray that misses it cannot hit the shape.
struct BoundingSphere {
  Vec3 center = Vec3::Zero();
  double radius = 0;
};

class Shape {
 public:
  virtual ~Shape() = default;
  // The nearest hit with t in (t_min, t_max), if any.
  virtual bool Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const = 0;
  virtual BoundingSphere Bounds() const = 0;
};

// A finite rectangle centred at `center`, spanned by unit axes u and v (normal u x v).
class RectangleShape final : public Shape {
 public:
  RectangleShape(const Vec3& center, const Vec3& axis_u, const Vec3& axis_v, double half_u,
                 double half_v);
  bool Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const override;
  BoundingSphere Bounds() const override;

 private:
  Vec3 center_, axis_u_, axis_v_, normal_;
  double half_u_, half_v_;
};

class BoxShape final : public Shape {
 public:
  BoxShape(const Vec3& min_corner, const Vec3& max_corner);
  bool Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const override;
  BoundingSphere Bounds() const override;

 private:
  Vec3 min_, max_;
};

class SphereShape final : public Shape {
 public:
  SphereShape(const Vec3& center, double radius);
  bool Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const override;
  BoundingSphere Bounds() const override;

 private:
  Vec3 center_;
  double radius_;
};

// An upright (+y) cone standing on a closed circular base.
class ConeShape final : public Shape {
 public:
  ConeShape(const Vec3& base_center, double radius, double height);
  bool Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const override;
  BoundingSphere Bounds() const override;

 private:
  Vec3 base_;
  double radius_, height_;
};

class DiscShape final : public Shape {
 public:
  DiscShape(const Vec3& center, const Vec3& normal, double radius);
  bool Intersect(const Ray& ray, double t_min, double t_max, SurfaceHit* hit) const override;
  BoundingSphere Bounds() const override;

 private:
  Vec3 center_, normal_, axis_u_, axis_v_;
  double radius_;
};

}  // namespace lfcam
