#pragma once
// How a command group plugs into cellctl: it adds its subcommands to the app and names, for each,
// the action main runs once parsing is done (after logging and signal handling are set up).

#include <CLI/CLI.hpp>
#include <functional>

#include "cli/options.hpp"

namespace cellctl::cli {

class Commands {
 public:
  GlobalOptions global;

  // When `sub` is chosen on the command line, run `action` and exit with what it returns.
  void on(CLI::App* sub, std::function<int()> action) {
    sub->callback([this, action = std::move(action)] { chosen_ = action; });
  }
  [[nodiscard]] const std::function<int()>& chosen() const noexcept { return chosen_; }

 private:
  std::function<int()> chosen_;
};

}  // namespace cellctl::cli
