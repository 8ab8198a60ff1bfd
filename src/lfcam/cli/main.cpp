// lfcam: a do-it-yourself 4D light field camera system. This file only parses and reports;
// the work is done by the library (src/lfcam/*).
#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <opencv2/core.hpp>

#include "lfcam/cli/commands.h"
#include "lfcam/core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"lfcam: capture, calibrate and render 4D light fields (An et al.'s DIY array)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "lfcam 0.1.0");
  lfcam::cli::AddSimulateCommand(app);
  lfcam::cli::AddRenderCommand(app);
  lfcam::cli::AddOracleCommand(app);
  lfcam::cli::AddInfoCommand(app);
  lfcam::cli::AddCompareCommand(app);
  lfcam::cli::AddMontageCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const lfcam::Error& e) {
    fmt::print(stderr, "lfcam: error: {}\n", e.what());
    return 1;
  } catch (const cv::Exception& e) {
    fmt::print(stderr, "lfcam: error (OpenCV): {}\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "lfcam: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
