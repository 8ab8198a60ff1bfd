// Every export read back as the tools that use it read it, and checked against the light field:
// a world point on the st-plane, projected with the exported camera of a view, lands on the pixel
// whose st sample it is; and that pixel holds the sample.
#include "lfcam/io/lightfield_export.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "lfcam/core/error.h"
#include "lfcam/io/colmap_text_test_support.h"
#include "lfcam/render/render_test_cases.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

fs::path Dir(const std::string& name) {
  return fs::temp_directory_path() / fmt::format("lfcam_export_{}_{}", name, ::getpid());
}

// The st samples a test checks in each view, and where they are in the world.
struct StProbe {
  int row, col, k, l;
};
std::vector<StProbe> StProbes(const LightField& lf) {
  const auto& d = lf.dims();
  return {{0, 0, 3, 5}, {d.rows - 1, d.cols - 1, d.n_s - 2, d.n_t - 3}, {2, 4, 40, 70}};
}
Vec3 WorldPoint(const LightField& lf, const StProbe& p) {
  return lf.slab().st.point_at(lf.s_of(p.k), lf.t_of(p.l));
}
cv::Vec3b Sample(const LightField& lf, const StProbe& p) {
  const std::uint8_t* s = lf.view_data(p.row, p.col) + 3 * (std::size_t(p.l) * lf.dims().n_s + p.k);
  return {s[2], s[1], s[0]};  // as OpenCV reads a PNG: BGR
}

// Projects with OpenCV's camera axes; `corner` is 0.5 for formats whose pixel corners are at
// integers (COLMAP, NeRF).
Vec2 Project(const Mat3& camera_from_world, const Vec3& t, double fx, double fy, double cx,
             double cy, const Vec3& x) {
  const Vec3 p = camera_from_world * x + t;
  return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy};
}

void ExpectProbesLand(const LightField& lf, const fs::path& dir, const std::string& image_folder,
                      const std::function<Vec2(int index, const Vec3&)>& project, double corner) {
  const auto& d = lf.dims();
  for (const StProbe& p : StProbes(lf)) {
    const int index = p.row * d.cols + p.col;
    const Vec2 pixel = project(index, WorldPoint(lf, p));
    EXPECT_NEAR(pixel.x(), p.k + corner, 1e-6) << p.row << "," << p.col;
    EXPECT_NEAR(pixel.y(), d.n_t - 1 - p.l + corner, 1e-6) << p.row << "," << p.col;
    const cv::Mat image = cv::imread(
        (dir / image_folder / fmt::format("view_{:02d}_{:02d}.png", p.row, p.col)).string());
    ASSERT_EQ(image.cols, d.n_s);
    EXPECT_EQ(image.at<cv::Vec3b>(d.n_t - 1 - p.l, p.k), Sample(lf, p));
  }
}

class Export : public ::testing::TestWithParam<bool> {
 protected:
  const LightField& Field() const {
    return GetParam() ? render_test::TurnedStPlaneLightField()
                      : render_test::SmallPaperLightField();
  }
};

TEST_P(Export, PngViewsAndTheirCamerasReadBack) {
  const LightField& lf = Field();
  const fs::path dir = Dir("png");
  fs::remove_all(dir);
  ExportLightField(lf, ExportFormat::kPngViews, dir);
  std::ifstream in(dir / "cameras.json");
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["views"].size(), lf.dims().view_count());
  ExpectProbesLand(
      lf, dir, "views",
      [&](int i, const Vec3& x) {
        const auto& v = j["views"][std::size_t(i)];
        Mat3 r;
        Vec3 c;
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b) r(a, b) = v["world_from_camera"][a][b];
          c(a) = v["world_from_camera"][a][3];
        }
        EXPECT_NEAR((c - lf.camera_center(v["row"], v["col"])).norm(), 0, 1e-9);
        return Project(r.transpose(), -(r.transpose() * c), v["fx"], v["fy"], v["cx"], v["cy"], x);
      },
      0.0);
  fs::remove_all(dir);
}

TEST_P(Export, NerfTransformsReadBack) {
  const LightField& lf = Field();
  const fs::path dir = Dir("nerf");
  fs::remove_all(dir);
  ExportLightField(lf, ExportFormat::kNerf, dir);
  std::ifstream in(dir / "transforms.json");
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["frames"].size(), lf.dims().view_count());
  EXPECT_GE(j["aabb_scale"].get<int>(), 1);
  ExpectProbesLand(
      lf, dir, "images",
      [&](int i, const Vec3& x) {
        const auto& f = j["frames"][std::size_t(i)];
        // OpenGL's camera-to-world (x right, y up, z back), metres -> OpenCV's, millimetres.
        Mat3 gl;
        Vec3 c;
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b) gl(a, b) = f["transform_matrix"][a][b];
          c(a) = 1000.0 * f["transform_matrix"][a][3].get<double>();
        }
        const Mat3 r = gl * Vec3(1, -1, -1).asDiagonal();
        return Project(r.transpose(), -(r.transpose() * c), f["fl_x"], f["fl_y"], f["cx"], f["cy"],
                       x);
      },
      0.5);
  fs::remove_all(dir);
}

TEST_P(Export, ColmapTextModelReadsBackInTheDocumentedFieldOrder) {
  const LightField& lf = Field();
  const fs::path dir = Dir("colmap");
  fs::remove_all(dir);
  ExportLightField(lf, ExportFormat::kColmap, dir);
  const auto cameras = testing::ReadColmapCameras(dir / "sparse/0/cameras.txt");
  for (const auto& [id, camera] : cameras) {
    EXPECT_EQ(camera.model, "PINHOLE");
    EXPECT_EQ(camera.width, lf.dims().n_s);
  }
  const auto images = testing::ReadColmapImages(dir / "sparse/0/images.txt");
  ASSERT_EQ(images.size(), lf.dims().view_count());
  for (const auto& [id, image] : images) EXPECT_TRUE(image.points.empty());  // no depth given
  EXPECT_TRUE(fs::exists(dir / "sparse/0/points3D.txt"));
  ExpectProbesLand(
      lf, dir, "images",
      [&](int i, const Vec3& x) {
        const testing::ColmapImage& im = images.at(i + 1);
        const auto& k = cameras.at(im.camera).params;
        EXPECT_TRUE(fs::exists(dir / "images" / im.name));
        return Project(im.camera_from_world, im.t, k[0], k[1], k[2], k[3], x);
      },
      0.5);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(FlatAndTurnedStPlane, Export, ::testing::Bool());

// A light field imported without a metric scale (lengths in units of the cameras' spacing):
// NeRF's frames keep those units rather than a thousandth of them (a scene far smaller than NeRF
// trainers expect), and the views' cameras.json says what its lengths are.
TEST(ExportWithoutAMetricScale, KeepsTheLightFieldsUnits) {
  LightField lf = render_test::SmallPaperLightField();
  lf.metadata()["import"]["length_unit"] = "units";
  ASSERT_EQ(WorldLengthUnit(lf.metadata()), "units");
  const fs::path dir = Dir("units");
  fs::remove_all(dir);
  ExportLightField(lf, ExportFormat::kNerf, dir);
  std::ifstream in(dir / "transforms.json");
  const auto j = nlohmann::json::parse(in);
  const Vec3 centre = lf.camera_center(0, 0);
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(j["frames"][0]["transform_matrix"][a][3].get<double>(), centre(a), 1e-9);
  fs::remove_all(dir);
  ExportLightField(lf, ExportFormat::kPngViews, dir);
  std::ifstream views(dir / "cameras.json");
  EXPECT_NE(nlohmann::json::parse(views)["units"].get<std::string>().find("cameras' spacing"),
            std::string::npos);
  fs::remove_all(dir);
}

TEST(ExportErrors, ANonEmptyFolderOrAnUnknownFormatIsRefused) {
  const fs::path dir = Dir("busy");
  fs::create_directories(dir);
  std::ofstream(dir / "keep.txt") << "mine";
  EXPECT_THROW(ExportLightField(render_test::SmallPaperLightField(), ExportFormat::kNerf, dir),
               Error);
  EXPECT_TRUE(fs::exists(dir / "keep.txt"));
  EXPECT_THROW(ExportFormatFromString("ply"), UsageError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam
