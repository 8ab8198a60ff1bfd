#pragma once
// A scene for the simulator: analytic shapes with procedural textures under a simple light,
// plus the ideal camera array and world board that go with it.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lfcam/core/slab.h"
#include "lfcam/sim/motion.h"
#include "lfcam/sim/shapes.h"
#include "lfcam/sim/texture.h"

namespace lfcam {

struct SceneObject {
  std::string name;
  std::shared_ptr<const Shape> shape;
  Texture texture;
  std::optional<Motion> motion;  // how it moves over time (Scene::AtTime); none: it stays
};

// The ideal rig a scene is laid out for: the camera array (uv-plane) and the world board
// whose squared area is the view window (st-plane, world z = 0).
struct SceneRig {
  ArrayPlane array;
  ViewWindow board;
  int board_inner_corners_x = 11;  // OpenCV's convention: inner corners
  int board_inner_corners_y = 10;
  double board_square_mm = 50.0;
};

class Scene {
 public:
  std::string name;
  SceneRig rig;
  std::vector<SceneObject> objects;
  Vec3 background = Vec3(0.02, 0.02, 0.03);                  // linear radiance of rays that miss
  Vec3 light_direction = Vec3(-0.4, 0.7, 0.6).normalized();  // toward the light
  double ambient = 0.35;

  // Objects that exist only in the scene at a time (a ball crossing it): a still of the scene
  // (the scene itself, as every still light field and test renders it) leaves them out, and
  // AtTime puts them in, moved.
  std::vector<SceneObject> movers;

  void Add(std::string object_name, std::shared_ptr<const Shape> shape, const Texture& texture,
           std::optional<Motion> motion = std::nullopt) {
    objects.push_back({std::move(object_name), std::move(shape), texture, motion});
  }
  void AddMover(std::string object_name, std::shared_ptr<const Shape> shape, const Texture& texture,
                const Motion& motion) {
    movers.push_back({std::move(object_name), std::move(shape), texture, motion});
  }
  // The scene at time t (seconds from a recording's start): every moving object where its
  // motion puts it then, the movers in. A still scene of its own: the oracle, the depth truth
  // and the simulated cameras render it as they render any scene.
  Scene AtTime(double t_seconds) const;
  // Whether anything in it moves.
  bool moves() const;
  // Spheres that hold everything that moves: where each moving object and mover is at time t,
  // and where the still scene has each moving object. Outside them, the scene at t and the
  // still scene look the same.
  std::vector<BoundingSphere> MovingBounds(double t_seconds) const;
  // Linear RGB radiance arriving along `ray` (from its origin, t > 0).
  Vec3 Radiance(const Ray& ray) const;
  // The same from the objects `candidates` names alone (indices into `objects`, ascending):
  // equal to Radiance(ray), bit for bit, where no other object lies on the ray.
  Vec3 Radiance(const Ray& ray, std::span<const int> candidates) const;
  // Distance t of the first surface along `ray`, or +inf.
  double FirstHitDistance(const Ray& ray) const;
  // The first surface along `ray`: its distance t (+inf when none) and the index of its object
  // in `objects` (-1 when none).
  struct Hit {
    double t;
    int object;
  };
  Hit FirstHit(const Ray& ray) const;

  // The slab of the scene's ideal rig, with the given st domain.
  Slab IdealSlab(const StDomain& domain = {}) const { return {rig.array, rig.board, domain}; }

 private:
  // The shading of `best`, the surface of `found` a ray met first (the background without one).
  Vec3 Shade(const Ray& ray, const SceneObject* found, const SurfaceHit& best) const;
};

// The built-in scenes, by name ("paper"); throws lfcam::Error for an unknown name.
Scene MakeScene(const std::string& name);
std::vector<std::string> SceneNames();

// The paper's Fig. 11 layout: a 10x10, 28 mm array 3.6 m in front of the world board, with a
// coffee maker at 3.4 m, a marker cone at 3.7 m, a globe at 3.9 m, a fan at 4.7 m and a
// checkerboard at 5.2 m from the array, on a table, before a back wall.
Scene MakePaperScene();

}  // namespace lfcam
