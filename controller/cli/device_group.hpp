#pragma once
// What the commissioning command groups (scu, spindle, encoder) share: the port to talk to, how long
// to wait, and the group whose actions take those two options.

#include <CLI/CLI.hpp>
#include <chrono>
#include <optional>
#include <string>

#include "link/clock.hpp"

namespace cellctl::cli {

struct DeviceOptions {
  std::optional<std::string> port;  // overrides the cell config's
  double timeout_s = 10.0;

  [[nodiscard]] link::Duration timeout() const {
    return std::chrono::duration_cast<link::Duration>(std::chrono::duration<double>(timeout_s));
  }
};

// The command group `name` (scu, spindle, encoder) with --port and --timeout. Each action takes the
// two options as well, so they work where a person types them — `cellctl scu --port P status` and
// `cellctl scu status --port P` alike — and the action's --help lists them.
class DeviceGroup {
 public:
  DeviceGroup(CLI::App& app, const char* name, const char* help, DeviceOptions& options,
              const char* timeout_help)
      : group_(app.add_subcommand(name, help)), options_(options), timeout_help_(timeout_help) {
    group_->require_subcommand(1);
    add_options(*group_);
  }

  // Adds the action `name`; the caller adds its own options and its callback.
  CLI::App* add_action(const char* name, const char* help) {
    auto* action = group_->add_subcommand(name, help);
    add_options(*action);
    return action;
  }

 private:
  void add_options(CLI::App& command) {
    command.add_option("--port", options_.port, "Serial port (default: from the cell config)");
    command.add_option("--timeout", options_.timeout_s, timeout_help_)
        ->check(CLI::Range(0.1, 3600.0))
        ->capture_default_str();
  }

  CLI::App* group_;
  DeviceOptions& options_;
  const char* timeout_help_;
};

}  // namespace cellctl::cli
