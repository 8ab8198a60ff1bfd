#pragma once
// The flags that choose a built-in scene and its time, for the commands that simulate or render
// one (`simulate lightfield`, `oracle`).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "lfcam/sim/scene.h"

namespace lfcam::cli {

// --time T: the scene at T seconds (Scene::AtTime: its movers in, where they are then), 0 to
// 86400; without it the still scene.
void AddSceneTimeOption(CLI::App& command, std::optional<double>& time_s);

// The built-in scene `name` (--scene) at `time_s` (--time); a usage error names the flag at fault
// (an unknown scene, a time that is not a number).
Scene SceneAtTime(const std::string& name, const std::optional<double>& time_s);

}  // namespace lfcam::cli
