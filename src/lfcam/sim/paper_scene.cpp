// The `paper` scene: the layout of the paper's Fig. 11 (see docs/conventions.md for frames).
//
// World frame = the world board's: origin at the bottom-left outer corner of its squared area,
// x right, y up, z toward the array. The board (12 x 11 squares of 50 mm, 11 x 10 inner
// corners) is the view window, 600 x 550 mm at z = 0; the array's centre faces its centre
// from 3.6 m, so an object "d metres from the array" sits at z = 3600 - 1000 d.
#include <memory>

#include "lfcam/sim/scene.h"

namespace lfcam {
namespace {

constexpr double kArrayDistanceMm = 3600.0;
constexpr double kFloorY = 75.0;  // the table top, 200 mm below the array's centre

double ZAtDistance(double metres) { return kArrayDistanceMm - 1000.0 * metres; }

constexpr double kTwoPi = 6.283185307179586;

Texture Make(Pattern pattern, Vec3 a, Vec3 b, double scale_mm, unsigned seed = 1) {
  return Texture{pattern, a, b, scale_mm, seed};
}

}  // namespace

Scene MakePaperScene() {
  Scene scene;
  scene.name = "paper";
  scene.rig.board = ViewWindow{Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 600.0, 550.0};
  scene.rig.board_inner_corners_x = 11;
  scene.rig.board_inner_corners_y = 10;
  scene.rig.board_square_mm = 50.0;
  ArrayPlane& array = scene.rig.array;
  array.rows = array.cols = 10;
  array.pitch_mm = 28.0;
  array.u_ca = Vec3::UnitX();
  array.v_ca = Vec3::UnitY();
  array.n_ca = Vec3::UnitZ();
  const Vec3 array_center(300.0, 275.0, kArrayDistanceMm);
  array.p_ca =
      array_center - 0.5 * array.width_mm() * array.u_ca - 0.5 * array.height_mm() * array.v_ca;

  // Table top and back wall.
  scene.Add("table",
            std::make_shared<RectangleShape>(Vec3(300, kFloorY, -1150), Vec3::UnitX(),
                                             -Vec3::UnitZ(), 1800, 1750),
            Make(Pattern::kNoise, {0.30, 0.18, 0.09}, {0.62, 0.43, 0.24}, 30, 7));
  scene.Add("back wall",
            std::make_shared<RectangleShape>(Vec3(300, 1000, ZAtDistance(6.5)), Vec3::UnitX(),
                                             Vec3::UnitY(), 2500, 2000),
            Make(Pattern::kNoise, {0.18, 0.22, 0.28}, {0.62, 0.60, 0.52}, 60, 3));

  // Coffee maker, front face 3.4 m from the array: a box covered in text-like print.
  const double z_coffee = ZAtDistance(3.4);
  scene.Add("coffee maker",
            std::make_shared<BoxShape>(Vec3(120, kFloorY, z_coffee - 120),
                                       Vec3(220, kFloorY + 220, z_coffee)),
            Make(Pattern::kText, {0.07, 0.07, 0.08}, {0.85, 0.78, 0.55}, 9, 11));

  // Marker cone at 3.7 m: orange and white bands.
  scene.Add("marker cone",
            std::make_shared<ConeShape>(Vec3(260, kFloorY, ZAtDistance(3.7)), 45, 160),
            Make(Pattern::kStripes, {0.90, 0.22, 0.02}, {0.85, 0.85, 0.82}, 30));

  // Globe at 3.9 m, standing on the table.
  scene.Add("globe", std::make_shared<SphereShape>(Vec3(370, kFloorY + 90, ZAtDistance(3.9)), 90),
            Make(Pattern::kBlotchGrid, {0.04, 0.12, 0.45}, {0.20, 0.42, 0.08}, 25, 5));

  // Fan at 4.7 m: a bladed disc on a stand.
  const double z_fan = ZAtDistance(4.7);
  // It turns at 2 revolutions a second (in a scene at a time).
  const Vec3 fan_centre(420, kFloorY + 250, z_fan);
  Motion fan_turning;
  fan_turning.pivot = fan_centre;
  fan_turning.axis = Vec3::UnitZ();
  fan_turning.spin_rad_per_s = 2 * kTwoPi;
  scene.Add("fan", std::make_shared<DiscShape>(fan_centre, Vec3::UnitZ(), 120),
            Make(Pattern::kRadial, {0.75, 0.75, 0.80}, {0.12, 0.16, 0.30}, 12), fan_turning);
  scene.Add(
      "fan stand",
      std::make_shared<BoxShape>(Vec3(410, kFloorY, z_fan - 20), Vec3(430, kFloorY + 130, z_fan)),
      Make(Pattern::kConstant, {0.25, 0.25, 0.27}, {0, 0, 0}, 1));

  // Checkerboard at 5.2 m: 25 mm squares.
  scene.Add("checkerboard",
            std::make_shared<RectangleShape>(Vec3(240, kFloorY + 275, ZAtDistance(5.2)),
                                             Vec3::UnitX(), Vec3::UnitY(), 350, 275),
            Make(Pattern::kChecker, {0.80, 0.80, 0.80}, {0.03, 0.03, 0.03}, 25));

  // What moves only in a scene at a time (Scene::AtTime; a still leaves these out). A ball of
  // 40 mm radius flying across the scene 4.3 m from the array, 360 mm above the table, left to
  // right at 400 mm/s: at t = 0 it is out of the board's view, at x = -150, and it crosses the
  // 600 mm view window in about two seconds, before the checkerboard and the fan's top.
  Motion flying;
  flying.velocity_mm_per_s = Vec3(400, 0, 0);
  scene.AddMover("ball",
                 std::make_shared<SphereShape>(Vec3(-150, kFloorY + 360, ZAtDistance(4.3)), 40),
                 Make(Pattern::kBlotchGrid, {0.85, 0.20, 0.10}, {0.95, 0.85, 0.20}, 15, 9), flying);
  // A small fast thing, to show a sync error: a 12 mm bead on a 70 mm arm whirling at 5
  // revolutions a second (2.2 m/s; 0.7 mm in 0.3 ms) about a pivot before the checkerboard's
  // left half, at 4.4 m.
  Motion whirling;
  whirling.pivot = Vec3(110, kFloorY + 330, ZAtDistance(4.4));
  whirling.axis = Vec3::UnitZ();
  whirling.spin_rad_per_s = 5 * kTwoPi;
  scene.AddMover("bead", std::make_shared<SphereShape>(whirling.pivot + Vec3(70, 0, 0), 12),
                 Make(Pattern::kConstant, {0.95, 0.95, 0.15}, {0, 0, 0}, 1), whirling);
  return scene;
}

}  // namespace lfcam
