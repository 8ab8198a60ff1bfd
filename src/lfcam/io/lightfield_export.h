#pragma once
// Handing a light field to other tools (`lfcam export`, docs/format.md "Exporting"): each view
// is a perspective image from its camera's centre onto the st-plane (the st samples are its
// pixels), so it is an ordinary pinhole camera whose image plane is the st-plane: focal lengths
// and principal point per view, rotation shared. Exported as
//   png-views  views/view_RR_CC.png and cameras.json (lfcam's world frame, millimetres);
//   nerf       transforms.json (instant-ngp / nerfstudio: camera-to-world, OpenGL axes, metres)
//              and images/; with depth maps also sparse_pc.ply (the points, metres), named by
//              transforms.json's "ply_file_path" (nerfstudio);
//   colmap     sparse/0/{cameras,images,points3D}.txt (COLMAP's text model: PINHOLE cameras,
//              world-to-camera poses, millimetres; points and their tracks from depth maps when
//              given, io/sparse_points.h, else none) and images/.
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "lfcam/core/geometry.h"
#include "lfcam/core/lightfield.h"
#include "lfcam/depth/depth_set.h"

namespace lfcam {

enum class ExportFormat { kPngViews, kNerf, kColmap };
ExportFormat ExportFormatFromString(const std::string& name);  // throws lfcam::UsageError

// View (row, col) as a pinhole camera, OpenCV's conventions: x right, y down, z forward; pixel
// (0, 0) the centre of the top-left st sample (add 0.5 for COLMAP's and NeRF's pixel corners).
struct ViewCamera {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  Rigid3 world_from_camera;
};
ViewCamera ViewAsCamera(const LightField& lf, int row, int col);

// View (row, col)'s samples as an 8-bit sRGB RGB image, top row first (st rows run bottom-up).
cv::Mat ViewImage(const LightField& lf, int row, int col);

struct ExportReport {
  int views = 0;  // written as images (png-views: every view; nerf, colmap: the photographed)
  // COLMAP and NeRF: the views left out as filled from their neighbours (grid row, col)
  std::vector<std::pair<int, int>> filled_left_out;
  int points = 0;  // COLMAP's 3D points
  std::size_t observations = 0;
  std::filesystem::path main_file;  // cameras.json, transforms.json or sparse/0/images.txt
};

// Writes into `out_dir` (created; must be empty if it exists). Everything is written into a
// sibling temporary folder renamed into place at the end. `depth` (COLMAP and NeRF) gives
// points3D.txt or sparse_pc.ply their points. Throws lfcam::Error.
ExportReport ExportLightField(const LightField& lf, ExportFormat format,
                              const std::filesystem::path& out_dir,
                              const DepthSet* depth = nullptr);

}  // namespace lfcam
