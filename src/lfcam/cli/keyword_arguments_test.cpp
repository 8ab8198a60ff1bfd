// render's flags as keyword arguments (the Python module's lfcam.render): each keyword becomes
// its flag, the flags' own code checks it, and the messages name the keyword.
#include "lfcam/cli/keyword_arguments.h"

#include <gtest/gtest.h>

#include "lfcam/cli/import_flags.h"
#include "lfcam/cli/render_flags.h"
#include "lfcam/core/error.h"

namespace lfcam::cli {
namespace {

std::string MessageOf(const std::vector<KeywordArgument>& arguments) {
  try {
    ParseRenderKeywords(arguments);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(KeywordArguments, EachKeywordBecomesItsFlag) {
  const std::vector<std::string> args =
      FlagArguments(RenderKeywordTable(), {{"focal_length", 120.5},
                                           {"eye", std::vector<double>{-10, 0.25, 1e5}},
                                           {"size", std::vector<double>{640, 480}},
                                           {"no_breathing", true},
                                           {"antialias", false},
                                           {"integrator", std::string("cameras")},
                                           {"threads", 2LL},
                                           {"as_camera", std::vector<double>{1.5, 2}}});
  EXPECT_EQ(args,
            (std::vector<std::string>{"--focal-length=120.5", "--eye=-10,0.25,100000",
                                      "--size=640x480", "--no-breathing", "--integrator=cameras",
                                      "--threads=2", "--as-camera=1.5,2"}));
}

TEST(KeywordArguments, TheFlagsDefaultsAndChecksAreRenders) {
  const auto request = ParseRenderKeywords({{"aperture", 40.0},
                                            {"focus_distance", 3500LL},
                                            {"eye", std::vector<double>{-28, 0, 0}},
                                            {"integrator", std::string("cameras")},
                                            {"interpolation", std::string("quadrilinear")}});
  EXPECT_EQ(request->camera.aperture_mm, 40.0);
  EXPECT_EQ(request->camera.focus_distance_mm, 3500.0);
  EXPECT_EQ(request->camera.focal_length_mm, 500.0);  // render's default
  EXPECT_EQ(request->camera.eye, "-28,0,0");
  // As `lfcam render --integrator cameras --interpolation quadrilinear`: that lookup's limit.
  EXPECT_EQ(request->options.integrator, Integrator::kCamerasQuadrilinear);
  EXPECT_EQ(request->chosen_backend, Backend::kCpu);
  const auto plain = ParseRenderKeywords({});
  EXPECT_EQ(plain->options.integrator, Integrator::kLensSamples);
  EXPECT_EQ(plain->options.interpolation, Interpolation::kQuadrilinear);
}

TEST(KeywordArguments, MistakesAreUsageErrorsNamingTheKeyword) {
  EXPECT_NE(MessageOf({{"focal_lenght", 50.0}}).find("'focal_lenght' is not a keyword of render"),
            std::string::npos);
  EXPECT_NE(MessageOf({{"focal_length", -5.0}}).find("focal_length: -5 must be a positive"),
            std::string::npos)
      << MessageOf({{"focal_length", -5.0}});
  EXPECT_NE(MessageOf({{"aperture", std::string("wide")}}).find("aperture"), std::string::npos);
  EXPECT_EQ(MessageOf({{"aperture", std::string("wide")}}).find("--aperture"), std::string::npos);
  EXPECT_NE(MessageOf({{"eye", std::vector<double>{1, 2}}}).find("eye: expected 3 numbers"),
            std::string::npos);
  EXPECT_NE(MessageOf({{"no_breathing", 1.0}}).find("no_breathing: expected True or False"),
            std::string::npos);
  EXPECT_NE(MessageOf({{"focal_length", true}}).find("focal_length: expected a value"),
            std::string::npos);
  EXPECT_NE(MessageOf({{"size", std::vector<double>{640.5, 480}}}).find("size: expected 2 whole"),
            std::string::npos);
  EXPECT_NE(MessageOf({{"aperture", 1.0}, {"aperture", 2.0}}).find("aperture: given twice"),
            std::string::npos);
  EXPECT_NE(MessageOf({{"integrator", std::string("magic")}}).find("integrator"),
            std::string::npos);
  EXPECT_NE(MessageOf({{"backend", std::string("gl")}, {"reference", true}}).find("reference"),
            std::string::npos);
  EXPECT_NE(MessageOf({{"antialias", true}}).find("antialias: only with interpolation depth"),
            std::string::npos)
      << MessageOf({{"antialias", true}});
  EXPECT_NE(MessageOf({{"depth_blend", std::string("four")}})
                .find("depth_blend: only with interpolation depth"),
            std::string::npos)
      << MessageOf({{"depth_blend", std::string("four")}});
  EXPECT_NE(
      MessageOf({{"interpolation", std::string("depth")}, {"depth_blend", std::string("all")}})
          .find("unknown depth blend 'all'"),
      std::string::npos)
      << MessageOf({{"interpolation", std::string("depth")}, {"depth_blend", std::string("all")}});
  EXPECT_NE(MessageOf({{"focus_distance", std::string("3000:4000")}}).find("focus_distance"),
            std::string::npos);
}

TEST(KeywordArguments, ImportTakesImportsFlags) {
  const auto request =
      ParseImportKeywords("views", {{"rig", std::string("parallel")},
                                    {"st_domain", std::vector<double>{-0.5, -0.5, 1.5, 1.5}},
                                    {"st_res", std::vector<double>{320, 240}},
                                    {"grid", std::vector<double>{1, 9}},
                                    {"allow_missing", true},
                                    {"keep_dark_views", true},
                                    {"lenslet", 14.0}});
  EXPECT_EQ(request->flags.dir, "views");
  EXPECT_EQ(request->flags.rig, "parallel");
  EXPECT_EQ(request->flags.st_domain, "-0.5,-0.5,1.5,1.5");
  EXPECT_EQ(request->flags.st_res, "320x240");
  EXPECT_EQ(request->flags.grid_shape, "1x9");  // rows x columns
  EXPECT_TRUE(request->flags.allow_missing);
  EXPECT_TRUE(request->flags.keep_dark_views);  // documented since stop 72, refused until 73
  EXPECT_EQ(request->flags.lenslet, 14);
  try {
    ParseImportKeywords("views", {{"aperture", 1.0}});
    ADD_FAILURE() << "import took a render keyword";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("'aperture' is not a keyword of import_views"),
              std::string::npos)
        << e.what();
  }
}

TEST(KeywordArguments, MessagesNameKeywordsNotFlags) {
  EXPECT_EQ(
      InKeywords(RenderKeywordTable(), "--focus-distance: 10 mm must exceed the focal length"),
      "focus_distance: 10 mm must exceed the focal length");
  EXPECT_EQ(InKeywords(RenderKeywordTable(), "--camera x.json and --as-camera"),
            "camera x.json and as_camera");
  EXPECT_EQ(InKeywords(RenderKeywordTable(), "--cameras-quadrilinear"),
            "--cameras-quadrilinear");  // not a flag
}

}  // namespace
}  // namespace lfcam::cli
