#pragma once
// A physical camera module, in OpenCV's conventions (docs/conventions.md): the camera frame has
// x right, y down and z forward (the viewing direction); pixel (0, 0) is the centre of the
// top-left pixel; distortion is Brown-Conrady with OpenCV's coefficients (k1, k2, p1, p2, k3).
//
//   x_n = (X / Z, Y / Z),  r^2 = |x_n|^2
//   x_d = x_n (1 + k1 r^2 + k2 r^4 + k3 r^6) + (2 p1 x y + p2 (r^2 + 2 x^2), p1 (r^2 + 2 y^2) + 2
//   p2 x y) pixel = (fx x_d + cx, fy y_d + cy)
#include <array>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "lfcam/core/geometry.h"

namespace lfcam {

struct Distortion {
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;

  // OpenCV's order: k1, k2, p1, p2, k3.
  std::array<double, 5> opencv() const { return {k1, k2, p1, p2, k3}; }
  bool is_zero() const { return k1 == 0 && k2 == 0 && p1 == 0 && p2 == 0 && k3 == 0; }
  // Normalised undistorted -> normalised distorted image coordinates.
  Vec2 Apply(const Vec2& undistorted) const;
  // The inverse, by fixed-point iteration; nullopt where it does not converge (far outside the
  // image, where the polynomial folds back).
  std::optional<Vec2> Remove(const Vec2& distorted) const;
};

struct CameraIntrinsics {
  int width = 0, height = 0;  // pixels
  double fx = 0, fy = 0, cx = 0, cy = 0;
  Distortion distortion;

  Mat3 K() const;
  // Camera-frame point -> pixel; nullopt behind the camera (Z <= 0).
  std::optional<Vec2> Project(const Vec3& camera_point) const;
  // Pixel -> direction in the camera frame (Z = 1); nullopt where distortion cannot be undone.
  std::optional<Vec3> Unproject(const Vec2& pixel) const;
  bool contains(const Vec2& pixel) const {
    return pixel.x() >= -0.5 && pixel.y() >= -0.5 && pixel.x() <= width - 0.5 &&
           pixel.y() <= height - 0.5;
  }
};

// The rotation that makes a camera look along -n (x along `right`): the ideal orientation of a
// module in an array whose plane has unit vectors u_ca (right), v_ca (up), n_ca (back).
Mat3 WorldFromCameraRotation(const Vec3& u_ca, const Vec3& v_ca, const Vec3& n_ca);

// Rotation matrix <-> angle-axis vector (radians times the unit axis).
Mat3 RotationFromAngleAxis(const Vec3& angle_axis);
Vec3 AngleAxisFromRotation(const Mat3& rotation);

// JSON: {"width", "height", "fx", "fy", "cx", "cy", "distortion": [k1, k2, p1, p2, k3]}.
nlohmann::json IntrinsicsToJson(const CameraIntrinsics& intrinsics);
// Reads with the bounded readers of core/json_input.h; throws lfcam::Error naming `where`.
CameraIntrinsics IntrinsicsFromJson(const nlohmann::json& j, const std::string& where);
// A rotation as 3 rows of 3; read back, it must be orthonormal with determinant +1.
nlohmann::json RotationToJson(const Mat3& rotation);
Mat3 RotationFromJson(const nlohmann::json& j, const std::string& where);

}  // namespace lfcam
