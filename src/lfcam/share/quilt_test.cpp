#include "lfcam/share/quilt.h"

#include <gtest/gtest.h>

#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

// Where a world point falls on a camera's film, in pixels (x right, y up from the bottom-left).
Vec2 Project(const VirtualCamera& camera, const Vec3& point) {
  const Vec3 d = point - camera.e_c();
  const Vec3 along = d / -d.dot(camera.n_c());  // its component along -n_c is 1
  const double tan_x = std::tan(0.5 * camera.field_of_view_rad());
  const double tan_y = tan_x * camera.height() / camera.width();
  const Vec2 offset = camera.params().principal_offset_px;
  return {offset.x() + 0.5 * camera.width() * (along.dot(camera.u_c()) / tan_x + 1.0),
          offset.y() + 0.5 * camera.height() * (along.dot(camera.v_c()) / tan_y + 1.0)};
}

TEST(Quilt, PresetsLayOutTheirGridsAndNameThemAsTheDisplaysExpect) {
  const QuiltLayout portrait = LayoutQuilt(QuiltPresetNamed("portrait"));
  EXPECT_EQ(portrait.views(), 48);
  EXPECT_EQ(portrait.tile_width, 420);
  EXPECT_EQ(portrait.tile_height, 560);
  EXPECT_EQ(portrait.render_height, 560) << "the Portrait's tiles have its aspect";
  EXPECT_EQ(portrait.suffix(), "_qs8x6a0.75");
  const QuiltLayout go = LayoutQuilt(QuiltPresetNamed("go"));
  EXPECT_EQ(go.suffix(), "_qs11x6a0.5625");
  EXPECT_EQ(go.tile_width, 372);
  EXPECT_EQ(go.render_height, 661) << "rendered at the display's aspect, scaled into the tile";
  const QuiltLayout wide = LayoutQuilt(QuiltPresetNamed("16-landscape"), /*even=*/true);
  EXPECT_EQ(wide.suffix(), "_qs7x7a1.77778");
  EXPECT_EQ(wide.width() % 2, 0);
  EXPECT_EQ(wide.height() % 2, 0);
  EXPECT_NE(testing::ErrorOf([] { QuiltPresetNamed("hologram"); }).find("one of portrait, go"),
            std::string::npos);
}

TEST(Quilt, TilesRunLeftToRightFromTheBottomLeft) {
  const QuiltLayout layout = LayoutQuilt(QuiltPresetNamed("portrait"));
  EXPECT_EQ(QuiltTile(layout, 0), cv::Rect(0, 3360 - 560, 420, 560));
  EXPECT_EQ(QuiltTile(layout, 1), cv::Rect(420, 3360 - 560, 420, 560));
  EXPECT_EQ(QuiltTile(layout, 8), cv::Rect(0, 3360 - 1120, 420, 560));
  EXPECT_EQ(QuiltTile(layout, 47), cv::Rect(7 * 420, 0, 420, 560));
}

TEST(Quilt, ViewsAreOffAxisCamerasSharingTheWindowOnThePlaneOfFocus) {
  const QuiltLayout layout = LayoutQuilt(QuiltPresetNamed("portrait"));
  VirtualCameraParams centre;
  centre.eye = Vec3(300, 270, 3600);
  centre.look_at = Vec3(300, 270, -700);
  centre.focal_length_mm = 400;
  centre.focus_distance_mm = 4300;
  const std::vector<VirtualCameraParams> cameras = QuiltCameras(centre, layout, 252.0);
  ASSERT_EQ(cameras.size(), 48u);
  EXPECT_NEAR(cameras.front().eye.x(), 300 - 126, 1e-9) << "view 0 is the leftmost";
  EXPECT_NEAR(cameras.back().eye.x(), 300 + 126, 1e-9);
  for (const auto& c : cameras) EXPECT_NEAR(c.eye.y(), 270, 1e-9) << "a horizontal line";
  // Points on the plane of focus land on the same pixel in every view (zero parallax); points
  // nearer move against the eye, farther ones with it.
  const VirtualCamera first(cameras.front()), last(cameras.back());
  for (const Vec3& p : {Vec3(300, 270, -700), Vec3(150, 400, -700), Vec3(420, 180, -700)})
    EXPECT_LT((Project(first, p) - Project(last, p)).norm(), 1e-6);
  const Vec3 near(300, 270, 0), far(300, 270, -2000);
  EXPECT_GT(Project(first, near).x(), Project(last, near).x());
  EXPECT_LT(Project(first, far).x(), Project(last, far).x());
  // Every view looks the same way as the centre (no toe-in).
  for (const auto& c : cameras)
    EXPECT_TRUE((c.look_at - c.eye).normalized().isApprox(Vec3(0, 0, -1), 1e-12));
}

}  // namespace
}  // namespace lfcam
