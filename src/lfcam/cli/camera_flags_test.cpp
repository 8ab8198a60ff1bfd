// The camera flags parsed on their own (ParseCameraFlags), as the fuzz targets of the flags and
// of the Python module's keywords parse them.
#include "lfcam/cli/camera_flags.h"

#include <gtest/gtest.h>

#include "lfcam/core/error.h"

namespace lfcam::cli {
namespace {

TEST(ParseCameraFlags, ParsesAsTheCommandsDoAndRefusesWhatTheyRefuse) {
  // As typed, first to last; with sweeps a range is swept, its start the camera's.
  const auto swept =
      ParseCameraFlags({"--focus-distance", "3000:5000", "--aperture", "64", "--eye", "10,20,3600"},
                       /*rig_cameras=*/true, /*sweeps=*/true);
  swept->flags.Validate();
  EXPECT_TRUE(swept->flags.given("--aperture"));
  EXPECT_FALSE(swept->flags.given("--look-at"));
  EXPECT_DOUBLE_EQ(swept->flags.aperture_mm, 64.0);
  const CameraSweep sweep = swept->flags.sweep();
  ASSERT_TRUE(sweep.focus_distance_mm.has_value());
  EXPECT_DOUBLE_EQ(sweep.focus_distance_mm->first, 3000.0);
  EXPECT_DOUBLE_EQ(sweep.focus_distance_mm->second, 5000.0);
  EXPECT_FALSE(sweep.aperture_mm.has_value());
  EXPECT_DOUBLE_EQ(swept->flags.MakeCamera(ArrayPlane{}).params().focus_distance_mm, 3000.0);

  // Without sweeps a range is no number; a flag that is not a camera's is refused, or left over
  // with allow_extras; a parse error is a UsageError naming the flag.
  const auto refused = [](const std::vector<std::string>& args, bool allow_extras,
                          const std::string& what) {
    try {
      ParseCameraFlags(args, false, false, allow_extras)->flags.Validate();
      ADD_FAILURE() << "accepted " << args.front();
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused({"--focus-distance", "3000:5000"}, false, "--focus-distance");
  refused({"--integrator", "cameras"}, false, "--integrator");
  refused({"--as-camera", "1,1"}, false, "--as-camera");  // only with rig_cameras
  EXPECT_NO_THROW(ParseCameraFlags({"--integrator", "cameras", "--aperture", "32"}, false, false,
                                   /*allow_extras=*/true)
                      ->flags.Validate());
}

}  // namespace
}  // namespace lfcam::cli
