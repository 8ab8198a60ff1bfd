#pragma once
// Tests only: COLMAP's text model read back in the format's documented field order, as COLMAP
// and the Gaussian-splatting trainers read it (the exports' tests).
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "lfcam/core/geometry.h"

namespace lfcam::testing {

// cameras.txt: CAMERA_ID MODEL WIDTH HEIGHT PARAMS[] (PINHOLE: fx fy cx cy).
struct ColmapCamera {
  std::string model;
  int width = 0, height = 0;
  std::array<double, 4> params{};
};
inline std::map<int, ColmapCamera> ReadColmapCameras(const std::filesystem::path& path) {
  std::map<int, ColmapCamera> cameras;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    int id = 0;
    ColmapCamera c;
    s >> id >> c.model >> c.width >> c.height >> c.params[0] >> c.params[1] >> c.params[2] >>
        c.params[3];
    cameras[id] = c;
  }
  return cameras;
}

// images.txt: IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME, then a line of X Y POINT3D_ID.
struct ColmapImage {
  Mat3 camera_from_world;
  Vec3 t;
  int camera = 0;
  std::string name;
  std::vector<std::pair<Vec2, int>> points;
};
inline std::map<int, ColmapImage> ReadColmapImages(const std::filesystem::path& path) {
  std::map<int, ColmapImage> images;
  std::ifstream in(path);
  int current = -1;  // the image whose line of points comes next
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] == '#') continue;
    std::istringstream s(line);
    if (current < 0) {
      double qw, qx, qy, qz;
      ColmapImage im;
      s >> current >> qw >> qx >> qy >> qz >> im.t.x() >> im.t.y() >> im.t.z() >> im.camera >>
          im.name;
      im.camera_from_world = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
      images[current] = im;
    } else {
      double x, y;
      int id;
      while (s >> x >> y >> id) images[current].points.push_back({Vec2(x, y), id});
      current = -1;
    }
  }
  return images;
}

}  // namespace lfcam::testing
