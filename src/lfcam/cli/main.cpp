// lfcam: a do-it-yourself 4D light field camera system. This file only parses and reports;
// the work is done by the library (src/lfcam/*).
//
// Exit status (docs/cli.md): 0 success, 1 an error in the work (a corrupt or missing input, a
// failed write, a resource limit), 2 bad usage (unknown command or flag, a flag's value out of
// range). A signal that ends lfcam leaves no temporary file behind (core/signal_cleanup.h).
#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string_view>

#include "lfcam/cli/commands.h"
#include "lfcam/core/error.h"
#include "lfcam/core/freed_memory.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/signal_cleanup.h"

namespace {

constexpr int kExitError = 1;
constexpr int kExitUsage = 2;

// Reports an error in the way the user asked for: JSON on stdout under --json, else a line on
// stderr. Returns the exit status.
int Report(bool json, int status, const std::string& message) {
  if (json)
    fmt::print("{}\n", lfcam::JsonToText({{"error", message}, {"exit_status", status}}, 2));
  else
    fmt::print(stderr, "lfcam: error: {}\n", message);
  return status;
}

bool WantsJson(int argc, char** argv) {
  // `bench --json FILE` names an output file; its messages stay text.
  if (argc > 1 && std::strcmp(argv[1], "bench") == 0) return false;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--json") == 0) return true;
  return false;
}

// `lfcam help [COMMAND [SUBCOMMAND]]`: the help of the app or of one command.
void AddHelpCommand(CLI::App& app) {
  auto* help = app.add_subcommand("help", "Show the commands, or one command's flags");
  auto words = std::make_shared<std::vector<std::string>>();
  help->add_option("command", *words,
                   "A command (and subcommand), e.g. render or simulate lightfield");
  help->callback([&app, help, words] {
    const CLI::App* target = &app;
    std::string usage = app.get_name();
    for (const auto& word : *words) {
      const CLI::App* next = nullptr;
      for (const CLI::App* sub : target->get_subcommands({}))
        if (sub->get_name() == word) next = sub;
      if (!next || next == help)
        throw lfcam::UsageError(fmt::format("help: no command '{}' (try `lfcam help`)", word));
      target = next;
      usage += " " + word;
    }
    // The formatter directly: App::help() would describe the selected subcommand, `help` itself.
    fmt::print("{}", target->get_formatter()->make_help(target, usage, CLI::AppFormatMode::Normal));
  });
}

}  // namespace

int main(int argc, char** argv) {
  lfcam::KeepFreedMemoryForReuse();
  lfcam::InstallSignalCleanup();
  CLI::App app{"lfcam: capture, calibrate and render 4D light fields (An et al.'s DIY array)",
               "lfcam"};
  app.set_version_flag("--version", "lfcam " LFCAM_VERSION);
  app.footer(
      "Run `lfcam help COMMAND` for a command's flags.\n"
      "Exit status: 0 success, 1 an error in the work, 2 bad usage.");
  lfcam::cli::AddCaptureCommand(app);
  lfcam::cli::AddSimulateCommand(app);
  lfcam::cli::AddCalibrateCommand(app);
  lfcam::cli::AddBuildCommand(app);
  lfcam::cli::AddImportCommand(app);
  lfcam::cli::AddExportCommand(app);
  lfcam::cli::AddDepthCommand(app);
  lfcam::cli::AddRenderCommand(app);
  lfcam::cli::AddViewCommand(app);
  lfcam::cli::AddOracleCommand(app);
  lfcam::cli::AddInfoCommand(app);
  lfcam::cli::AddCompareCommand(app);
  lfcam::cli::AddMontageCommand(app);
  lfcam::cli::AddBenchCommand(app);
  AddHelpCommand(app);
  if (argc <= 1) {
    fmt::print("{}", app.help());
    return 0;
  }
  app.require_subcommand(1);
  const bool json = WantsJson(argc, argv);
  if (argv[1][0] != '-') {
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known |= sub->get_name() == argv[1];
    if (!known)
      return Report(json, kExitUsage,
                    fmt::format("'{}' is not an lfcam command (see `lfcam help`)", argv[1]));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    fmt::print("{}", app.help());
    return 0;
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help on a command, --version
    return Report(json, kExitUsage,
                  fmt::format("{} (see `lfcam help` or `lfcam COMMAND --help`)", e.what()));
  } catch (const lfcam::UsageError& e) {
    return Report(json, kExitUsage, e.what());
  } catch (const lfcam::Error& e) {
    return Report(json, kExitError, e.what());
  } catch (const std::bad_alloc&) {
    return Report(json, kExitError,
                  "out of memory: the work needs more memory than this machine can give (try a "
                  "smaller --size, light field or --lens-rate)");
  } catch (const cv::Exception& e) {
    return Report(json, kExitError,
                  fmt::format("image processing failed in {}: {}", e.func, e.err));
  } catch (const std::filesystem::filesystem_error& e) {
    return Report(json, kExitError, fmt::format("{}: {}", e.path1().string(), e.code().message()));
  } catch (const nlohmann::json::exception& e) {
    return Report(json, kExitError, fmt::format("internal error reading JSON (id {})", e.id));
  } catch (const std::exception& e) {
    return Report(json, kExitError, fmt::format("internal error: {}", e.what()));
  }
  return 0;
}
