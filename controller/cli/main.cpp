// cellctl: the motion-cell controller's command line. Each command group registers itself here.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <exception>

#include "cli/check_command.hpp"
#include "cli/commands.hpp"
#include "cli/compare_command.hpp"
#include "cli/drive.hpp"
#include "cli/emulate_command.hpp"
#include "cli/encoder_commands.hpp"
#include "cli/home_command.hpp"
#include "cli/logging.hpp"
#include "cli/report_command.hpp"
#include "cli/run_command.hpp"
#include "cli/scu_commands.hpp"
#include "cli/serve_command.hpp"
#include "cli/spindle_commands.hpp"
#include "cli/teach_in_command.hpp"
#include "cli/unknown_command.hpp"
#include "config/yaml_node.hpp"
#include "exit_codes/exit_codes.hpp"
#include "journal/version.hpp"
#include "link/crash_stop.hpp"
#include "link/link_error.hpp"

namespace cellctl::cli {
std::atomic<bool> g_interrupted{false};
std::atomic<bool> g_terminated{false};
}  // namespace cellctl::cli

namespace {
extern "C" void on_interrupt(int) {
  cellctl::cli::g_interrupted.store(true);
}
extern "C" void on_terminate(int) {
  cellctl::cli::g_terminated.store(true);
}
}  // namespace

int main(int argc, char** argv) {
  using namespace cellctl;
  using namespace cellctl::cli;
  // Before any port opens: a crash writes each open port's stop telegram, then dies (link/crash_stop.hpp).
  cellctl::link::crash_stop::install_handlers();
  CLI::App app{
      "cellctl — controller for a motion cell (Ewellix SCU actuators, SycoTec spindle, Scancon encoder)"};
  app.require_subcommand(1);
  // Global options where a person types them: `cellctl -c cell.yaml run R` and `cellctl run R -c cell.yaml`.
  app.fallthrough();
  app.set_version_flag("--version", "cellctl " + std::string(cellctl::journal::cellctl_version()));

  Commands commands;
  GlobalOptions& global = commands.global;
  app.add_option("-c,--config", global.config, "Cell configuration file")->capture_default_str();
  app.add_option("--log-level", global.log_level, "Console log level")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}))
      ->capture_default_str();
  app.add_flag("--trace", global.trace, "Hex trace of every telegram on every device link (to stderr)");

  add_run_command(app, commands);
  add_check_command(app, commands);
  add_home_command(app, commands);
  add_emulate_command(app, commands);
  add_spindle_commands(app, commands);
  add_encoder_commands(app, commands);
  add_teach_in_command(app, commands);
  add_serve_command(app, commands);
  add_scu_commands(app, commands);
  add_report_command(app, commands);
  add_compare_command(app, commands);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (const auto unknown = unknown_command_message(app)) {
      std::fprintf(stderr, "%s\n", unknown->c_str());
      return kExitUsage;
    }
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  init_logging(global.log_level, global.trace);
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_terminate);

  int code = kExitOk;
  try {
    code = commands.chosen()();
  } catch (const cellctl::config::ConfigError& e) {
    spdlog::error("{}", e.what());
    code = kExitConfig;
  } catch (const cellctl::link::LinkError& e) {
    spdlog::error("{}", e.what());
    code = kExitLink;
  } catch (const std::exception& e) {
    // Anything else that stops a command before it starts (an unwritable run record, a config the
    // sessions refuse): said plainly, never a crash.
    spdlog::error("{}", e.what());
    code = kExitFailed;
  }
  spdlog::shutdown();
  return code;
}
