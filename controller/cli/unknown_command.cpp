#include "cli/unknown_command.hpp"

#include <fmt/format.h>

#include <string_view>
#include <vector>

#include "config/closest_word.hpp"

namespace cellctl::cli {

std::optional<std::string> unknown_command_message(const CLI::App& app) {
  // The deepest command the parser took (cellctl, or `cellctl scu`): the word belongs to it.
  const CLI::App* group = &app;
  std::string path = "cellctl";  // as the user calls it, not the path it was started by
  for (auto taken = group->get_subcommands(); !taken.empty(); taken = group->get_subcommands()) {
    group = taken.front();
    path += " " + group->get_name();
  }
  if (group->get_require_subcommand_min() == 0 || !group->get_subcommands().empty()) return std::nullopt;
  // Words no command or option took travel up to the top (fallthrough); the first is the mistyped command.
  std::optional<std::string> typed;
  for (const auto& word : app.remaining())
    if (!word.empty() && word.front() != '-') {
      typed = word;
      break;
    }
  if (!typed) return std::nullopt;
  std::vector<std::string> names;
  for (const auto* sub : group->get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  const std::vector<std::string_view> words(names.begin(), names.end());
  const auto closest = config::closest_word(*typed, words);
  return fmt::format("{}: unknown command '{}'{}; `{} --help` lists the commands: {}", path, *typed,
                     closest.empty() ? "" : fmt::format(" (did you mean '{}'?)", closest), path,
                     fmt::join(names, ", "));
}

}  // namespace cellctl::cli
