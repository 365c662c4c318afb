#pragma once
// What the commissioning command groups (scu, spindle, encoder) share: the port to talk to, how long
// to wait, and the group with those two options.

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

// Adds the group `name` with --port and --timeout (whose help says what is waited for); the caller
// adds the subcommands.
inline CLI::App* add_device_group(CLI::App& app, const char* name, const char* help, DeviceOptions& options,
                                  const char* timeout_help) {
  auto* group = app.add_subcommand(name, help);
  group->require_subcommand(1);
  group->add_option("--port", options.port, "Serial port (default: from the cell config)");
  group->add_option("--timeout", options.timeout_s, timeout_help)
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  return group;
}

}  // namespace cellctl::cli
