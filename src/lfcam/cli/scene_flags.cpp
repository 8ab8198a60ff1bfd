#include "lfcam/cli/scene_flags.h"

#include <cmath>

#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"

namespace lfcam::cli {

void AddSceneTimeOption(CLI::App& command, std::optional<double>& time_s) {
  command
      .add_option("--time", time_s,
                  "The scene at this time, in seconds (its moving objects where they are then: "
                  "the paper scene's fan turns, a ball flies across it, a bead whirls); without "
                  "it, the still scene (none of the movers)")
      ->check(CLI::Range(0.0, 86400.0));
}

Scene SceneAtTime(const std::string& name, const std::optional<double>& time_s) {
  // CLI11's range lets NaN through (no comparison with it is true).
  if (time_s && !std::isfinite(*time_s))
    throw UsageError("--time: not a number of seconds (0 to 86400)");
  Scene scene = FlagValue("--scene", [&] { return MakeScene(name); });
  return time_s ? scene.AtTime(*time_s) : scene;
}

}  // namespace lfcam::cli
