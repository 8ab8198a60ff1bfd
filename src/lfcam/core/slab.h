#pragma once
// The two-plane slab of the paper (§5.1): the uv-plane is the PRP window spanned by the camera
// array, the st-plane is the view window on the world board (z = 0 of the world frame).
//
// Conventions (docs/conventions.md): camera (row, col) sits at
//   (u, v) = ((col + 0.5) / cols, (row + 0.5) / rows),
// (0, 0) at the bottom left seen from behind the array looking at the scene, u along columns
// (u_ca), v along rows (v_ca); n_ca points away from the scene, so cameras look along -n_ca.
#include <nlohmann/json_fwd.hpp>
#include <optional>

#include "lfcam/core/geometry.h"

namespace lfcam {

// The PRP window: the camera array's plane, with its grid.
struct ArrayPlane {
  Vec3 p_ca = Vec3::Zero();   // world position of the window's (u, v) = (0, 0) corner
  Vec3 u_ca = Vec3::UnitX();  // unit, along columns
  Vec3 v_ca = Vec3::UnitY();  // unit, along rows
  Vec3 n_ca = Vec3::UnitZ();  // unit, away from the scene
  int rows = 10;
  int cols = 10;
  double pitch_mm = 28.0;

  double width_mm() const { return cols * pitch_mm; }
  double height_mm() const { return rows * pitch_mm; }
  Vec3 point_at(double u, double v) const {
    return p_ca + u * width_mm() * u_ca + v * height_mm() * v_ca;
  }
  Vec3 center() const { return point_at(0.5, 0.5); }
  // World position of camera (row, col)'s centre of projection.
  Vec3 camera_center(int row, int col) const {
    return point_at((col + 0.5) / cols, (row + 0.5) / rows);
  }
};

// The view window: the squared area of the world board; (s, t) in [0, 1]^2 covers it.
struct ViewWindow {
  Vec3 origin = Vec3::Zero();   // world position of (s, t) = (0, 0): the board's bottom-left
  Vec3 x_axis = Vec3::UnitX();  // unit, along s
  Vec3 y_axis = Vec3::UnitY();  // unit, along t
  double width_mm = 600.0;
  double height_mm = 550.0;

  Vec3 normal() const { return x_axis.cross(y_axis).normalized(); }
  Vec3 point_at(double s, double t) const {
    return origin + s * width_mm * x_axis + t * height_mm * y_axis;
  }
};

// The sampled part of the st-plane, in view-window units; may exceed [0, 1]^2.
struct StDomain {
  double s0 = 0.0, t0 = 0.0, s1 = 1.0, t1 = 1.0;
  double s_extent() const { return s1 - s0; }
  double t_extent() const { return t1 - t0; }
};

// Where a line meets the two planes, in window coordinates.
struct SlabCoords {
  double u, v, s, t;
};

struct Slab {
  ArrayPlane uv;
  ViewWindow st;
  StDomain st_domain;

  // Coordinates of the line through `ray` on both planes, or nullopt if it runs parallel to
  // either. Inside-ness is not checked: see contains().
  std::optional<SlabCoords> intersect(const Ray& ray) const;
  // True when (u, v) lies in the PRP window and (s, t) in the sampled st domain.
  bool contains(const SlabCoords& c) const {
    return c.u >= 0.0 && c.u <= 1.0 && c.v >= 0.0 && c.v <= 1.0 && c.s >= st_domain.s0 &&
           c.s <= st_domain.s1 && c.t >= st_domain.t0 && c.t <= st_domain.t1;
  }
  // Distance between the planes along n_ca (the array's height above the board).
  double separation_mm() const { return n_ca_distance(st.origin); }
  double n_ca_distance(const Vec3& x) const { return uv.n_ca.dot(uv.p_ca - x); }

  // Throws lfcam::Error naming the field when the geometry is degenerate.
  void validate() const;
};

void to_json(nlohmann::json& j, const Slab& slab);
void from_json(const nlohmann::json& j, Slab& slab);

}  // namespace lfcam
