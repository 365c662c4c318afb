#pragma once
// When the command line names no command that exists: CLI11 says only "A subcommand is required".
// This names the word typed where the command belongs and the closest command (`cellctl reprot`:
// "unknown command 'reprot' (did you mean 'report'?)"), also inside a group (`cellctl scu mvoe`).

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace cellctl::cli {

// After app.parse() threw: the message for a word that names no command, or nullopt when the
// error is another one (then CLI11's own message stands).
[[nodiscard]] std::optional<std::string> unknown_command_message(const CLI::App& app);

}  // namespace cellctl::cli
