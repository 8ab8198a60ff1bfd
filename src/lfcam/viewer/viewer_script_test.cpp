// Viewer scripts: commands read and checked before any window opens, mistakes named by line.
#include "lfcam/viewer/viewer_script.h"

#include <gtest/gtest.h>

#include <string>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

TEST(ViewerScript, ReadsCommandsAndNamesTheLineOfAMistake) {
  const auto script = ParseViewerScript(
      "# a comment\n\nwindow 320 240\nset aperture 40\nclick 10 20\nwait\nquit\n", "s");
  ASSERT_EQ(script.size(), 5u);
  EXPECT_EQ(script[0].name, "window");
  EXPECT_EQ(script[2].args[1], "20");
  EXPECT_EQ(script[2].line, 5);
  const auto error = [](const std::string& text) {
    try {
      ParseViewerScript(text, "s.script");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("wait\nfly 1 2\n").find("s.script:2: unknown command 'fly'"), std::string::npos);
  EXPECT_NE(error("click 10\n").find("s.script:1: 'click' takes 2 arguments"), std::string::npos);
  EXPECT_NE(error("click ten 20\n").find("'ten' is not a number"), std::string::npos);
  EXPECT_NE(error("set aperture\n").find("'set' takes 2 arguments"), std::string::npos);
  EXPECT_NE(error("key F1\nkey Hyper\n").find("s.script:2: unknown key 'Hyper'"),
            std::string::npos);
  EXPECT_EQ(error("key F12\nkey w\nkey [\nkey Esc\n"), "");
}

}  // namespace
}  // namespace lfcam
