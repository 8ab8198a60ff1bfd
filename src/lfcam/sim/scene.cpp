#include "lfcam/sim/scene.h"

#include <fmt/format.h>

#include <limits>

#include "lfcam/core/error.h"

namespace lfcam {

double Scene::FirstHitDistance(const Ray& ray) const { return FirstHit(ray).t; }

Scene Scene::AtTime(double t_seconds) const {
  Scene at = *this;
  at.objects.clear();
  at.movers.clear();
  for (const std::vector<SceneObject>* list : {&objects, &movers})
    for (const SceneObject& o : *list) {
      SceneObject moved = o;
      if (o.motion) moved.shape = std::make_shared<MovedShape>(o.shape, o.motion->At(t_seconds));
      moved.motion.reset();
      at.objects.push_back(std::move(moved));
    }
  return at;
}

bool Scene::moves() const {
  if (!movers.empty()) return true;
  for (const SceneObject& o : objects)
    if (o.motion) return true;
  return false;
}

std::vector<BoundingSphere> Scene::MovingBounds(double t_seconds) const {
  std::vector<BoundingSphere> out;
  for (const SceneObject& o : objects)
    if (o.motion) {
      out.push_back(o.shape->Bounds());
      out.push_back(MovedShape(o.shape, o.motion->At(t_seconds)).Bounds());
    }
  for (const SceneObject& o : movers)
    out.push_back(o.motion ? MovedShape(o.shape, o.motion->At(t_seconds)).Bounds()
                           : o.shape->Bounds());
  return out;
}

namespace {

// The nearest of `objects` along `ray` among those `each` visits, and where it was hit.
template <typename EachObject>
const SceneObject* Nearest(const Ray& ray, EachObject each, SurfaceHit* best) {
  double nearest = std::numeric_limits<double>::infinity();
  const SceneObject* found = nullptr;
  SurfaceHit hit;
  each([&](const SceneObject& object) {
    if (object.shape->Intersect(ray, 1e-9, nearest, &hit)) {
      nearest = hit.t;
      *best = hit;
      found = &object;
    }
  });
  return found;
}

// Every object of `objects`, in order, for Nearest.
auto EveryObject(const std::vector<SceneObject>& objects) {
  return [&objects](auto visit) {
    for (const SceneObject& object : objects) visit(object);
  };
}

}  // namespace

Scene::Hit Scene::FirstHit(const Ray& ray) const {
  SurfaceHit best;
  const SceneObject* found = Nearest(ray, EveryObject(objects), &best);
  if (!found) return {std::numeric_limits<double>::infinity(), -1};
  return {best.t, int(found - objects.data())};
}

Vec3 Scene::Radiance(const Ray& ray) const {
  SurfaceHit best;
  const SceneObject* found = Nearest(ray, EveryObject(objects), &best);
  return Shade(ray, found, best);
}

Vec3 Scene::Radiance(const Ray& ray, std::span<const int> candidates) const {
  SurfaceHit best;
  const SceneObject* found = Nearest(
      ray,
      [&](auto visit) {
        for (const int i : candidates) visit(objects[std::size_t(i)]);
      },
      &best);
  return Shade(ray, found, best);
}

Vec3 Scene::Shade(const Ray& ray, const SceneObject* found, const SurfaceHit& best) const {
  if (!found) return background;
  Vec3 n = best.normal;
  if (n.dot(ray.direction) > 0) n = -n;  // two-sided surfaces
  const double diffuse = std::max(0.0, n.dot(light_direction));
  return found->texture.Evaluate(best.uv_mm) * (ambient + (1.0 - ambient) * diffuse);
}

std::vector<std::string> SceneNames() { return {"paper"}; }

Scene MakeScene(const std::string& name) {
  if (name == "paper") return MakePaperScene();
  throw Error(fmt::format("unknown scene '{}' (built-in scenes: paper)", name));
}

}  // namespace lfcam
