// COLMAP's points from depth maps, checked against the scene the simulator knows: every point
// lies on a surface, every view in its track sees it there unoccluded, and the exported text
// model reads back consistent (tracks and 2D points refer to each other, and re-projecting a
// point with an exported camera lands on its recorded pixel, which holds its colour).
#include "lfcam/io/sparse_points.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "lfcam/core/error.h"
#include "lfcam/io/colmap_text_test_support.h"
#include "lfcam/io/lightfield_export.h"
#include "lfcam/render/render_test_cases.h"
#include "lfcam/sim/depth_truth.h"
#include "lfcam/sim/scene.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

// The simulator's true depth for every view of the small paper light field.
DepthSet TrueDepth(const LightField& lf, const Scene& scene) {
  DepthSet set(lf.dims());
  for (int r = 0; r < lf.dims().rows; ++r)
    for (int c = 0; c < lf.dims().cols; ++c) set.set(GroundTruthDepth(scene, lf, r, c).map);
  return set;
}

TEST(SparsePoints, EveryPointIsOnASurfaceThatEveryViewOfItsTrackSees) {
  const LightField& lf = render_test::SmallPaperLightField();
  const Scene scene = MakePaperScene();
  const DepthSet depth = TrueDepth(lf, scene);
  SparsePointOptions options;
  options.stride = 4;
  const SparsePoints points = PointsFromDepth(lf, depth, options);
  ASSERT_GT(points.points.size(), 400u);
  std::size_t observations = 0;
  for (const auto& list : points.observations) observations += list.size();
  std::size_t in_tracks = 0, blocked = 0;
  for (std::size_t i = 0; i < points.points.size(); ++i) {
    const SparsePoint& p = points.points[i];
    ASSERT_FALSE(p.track.empty()) << "point " << i;  // at least the view it came from
    in_tracks += p.track.size();
    for (const auto& [view, index] : p.track) {
      const Vec3 eye = lf.camera_center(view / lf.dims().cols, view % lf.dims().cols);
      const double distance = (p.position_mm - eye).norm();
      // Nothing stands between the camera and the point, and the point is on what it hits;
      // but for the few views whose nearest sample saw past an edge that the exact ray grazes.
      const Scene::Hit hit = scene.FirstHit({eye, (p.position_mm - eye) / distance});
      blocked += !(std::abs(hit.t - distance) <= 0.01 * distance);
      const SparseObservation& o = points.observations[std::size_t(view)][std::size_t(index)];
      EXPECT_EQ(o.point, int(i));
    }
  }
  EXPECT_EQ(in_tracks, observations);
  EXPECT_LT(double(blocked), 0.001 * double(observations)) << blocked << " of " << observations;
  std::printf("%zu points, %zu observations, %zu of them past an edge\n", points.points.size(),
              observations, blocked);
  // Most points are seen by many views (the grid is 6 x 7; occlusions and the edges take some).
  EXPECT_GT(double(observations) / double(points.points.size()), 15.0);
}

TEST(SparsePoints, ColmapPointsAndTracksReadBackAndReprojectOntoTheirPixels) {
  const LightField& lf = render_test::SmallPaperLightField();
  const Scene scene = MakePaperScene();
  const DepthSet depth = TrueDepth(lf, scene);
  const fs::path dir =
      fs::temp_directory_path() / fmt::format("lfcam_sparse_points_{}", ::getpid());
  fs::remove_all(dir);
  const ExportReport report = ExportLightField(lf, ExportFormat::kColmap, dir, &depth);
  ASSERT_GT(report.points, 100);

  const auto cameras = testing::ReadColmapCameras(dir / "sparse/0/cameras.txt");
  const auto images = testing::ReadColmapImages(dir / "sparse/0/images.txt");
  ASSERT_EQ(images.size(), lf.dims().view_count());
  // points3D.txt: POINT3D_ID X Y Z R G B ERROR (IMAGE_ID POINT2D_IDX)...
  std::ifstream pts(dir / "sparse/0/points3D.txt");
  int count = 0, colour_matches = 0;
  std::map<int, cv::Mat> pictures;
  for (std::string line; std::getline(pts, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    int id, red, green, blue;
    double error;
    Vec3 x;
    s >> id >> x.x() >> x.y() >> x.z() >> red >> green >> blue >> error;
    ++count;
    EXPECT_EQ(id, count);
    bool colour_found = false;
    int image_id, index, track = 0;
    while (s >> image_id >> index) {
      ++track;
      ASSERT_TRUE(images.count(image_id)) << "point " << id;
      const testing::ColmapImage& im = images.at(image_id);
      ASSERT_LT(std::size_t(index), im.points.size()) << "point " << id;
      const auto& [pixel, back] = im.points[std::size_t(index)];
      EXPECT_EQ(back, id) << "point " << id << " in image " << image_id;
      // Re-projected with the exported camera, the point lands on the pixel recorded for it.
      const auto& k = cameras.at(im.camera).params;
      const Vec3 q = im.camera_from_world * x + im.t;
      EXPECT_NEAR(k[0] * q.x() / q.z() + k[2], pixel.x(), 2e-3) << "point " << id;
      EXPECT_NEAR(k[1] * q.y() / q.z() + k[3], pixel.y(), 2e-3) << "point " << id;
      // The view it came from holds its colour at that pixel (pixel centres at .5).
      if (!pictures.count(image_id))
        pictures[image_id] = cv::imread((dir / "images" / im.name).string());
      const cv::Vec3b bgr = pictures[image_id].at<cv::Vec3b>(int(pixel.y()), int(pixel.x()));
      colour_found |= bgr == cv::Vec3b(std::uint8_t(blue), std::uint8_t(green), std::uint8_t(red));
    }
    EXPECT_GT(track, 0) << "point " << id;
    colour_matches += colour_found;
  }
  EXPECT_EQ(count, report.points);
  EXPECT_EQ(colour_matches, count);
  fs::remove_all(dir);
}

TEST(SparsePoints, NerfGetsThemAsAPlyNamedInTransformsInMetres) {
  const LightField& lf = render_test::SmallPaperLightField();
  const DepthSet depth = TrueDepth(lf, MakePaperScene());
  const fs::path dir = fs::temp_directory_path() / fmt::format("lfcam_sparse_nerf_{}", ::getpid());
  fs::remove_all(dir);
  const ExportReport report = ExportLightField(lf, ExportFormat::kNerf, dir, &depth);
  const auto transforms = nlohmann::json::parse(std::ifstream(dir / "transforms.json"));
  ASSERT_EQ(transforms.value("ply_file_path", ""), "sparse_pc.ply");
  // The PLY's header, then x y z red green blue per vertex: the points, in metres.
  std::ifstream ply(dir / "sparse_pc.ply");
  std::string line;
  std::size_t vertices = 0;
  std::vector<std::string> properties;
  while (std::getline(ply, line) && line != "end_header") {
    std::istringstream s(line);
    std::string word, type, name;
    s >> word;
    if (word == "element") s >> type >> vertices;
    if (word == "property") s >> type >> name, properties.push_back(type + " " + name);
  }
  EXPECT_EQ(properties, (std::vector<std::string>{"float x", "float y", "float z", "uchar red",
                                                  "uchar green", "uchar blue"}));
  const SparsePoints points = PointsFromDepth(lf, depth);
  ASSERT_EQ(vertices, points.points.size());
  ASSERT_EQ(int(vertices), report.points);
  for (const SparsePoint& p : points.points) {
    Vec3 x;
    int red, green, blue;
    ASSERT_TRUE(ply >> x.x() >> x.y() >> x.z() >> red >> green >> blue);
    EXPECT_LT((x * 1000.0 - p.position_mm).norm(), 1e-6 * p.position_mm.norm() + 1e-3);
    EXPECT_EQ(cv::Vec3b(std::uint8_t(red), std::uint8_t(green), std::uint8_t(blue)), p.rgb);
  }
  fs::remove_all(dir);
}

TEST(SparsePoints, DepthOfAnotherLightFieldOrFormatIsRefused) {
  const LightField& lf = render_test::SmallPaperLightField();
  const fs::path dir = fs::temp_directory_path() / fmt::format("lfcam_sparse_bad_{}", ::getpid());
  LightFieldDims other = lf.dims();
  other.n_s += 1;
  const DepthSet wrong(other);
  EXPECT_THROW(ExportLightField(lf, ExportFormat::kColmap, dir, &wrong), Error);
  const DepthSet right(lf.dims());
  EXPECT_THROW(ExportLightField(lf, ExportFormat::kPngViews, dir, &right), Error);
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
}  // namespace lfcam
