#pragma once
// Each subcommand registers its flags and its action on the root app.
#include <CLI/CLI.hpp>

namespace lfcam::cli {

void AddSimulateCommand(CLI::App& app);
void AddSimulateCaptureCommand(CLI::App& simulate);  // `simulate capture`, under `simulate`
void AddCalibrateCommand(CLI::App& app);
void AddBuildCommand(CLI::App& app);
void AddRenderCommand(CLI::App& app);
void AddViewCommand(CLI::App& app);
void AddOracleCommand(CLI::App& app);
void AddInfoCommand(CLI::App& app);
void AddCompareCommand(CLI::App& app);
void AddMontageCommand(CLI::App& app);
void AddBenchCommand(CLI::App& app);
void AddCaptureCommand(CLI::App& app);
void AddImportCommand(CLI::App& app);
void AddExportCommand(CLI::App& app);
void AddDepthCommand(CLI::App& app);

}  // namespace lfcam::cli
