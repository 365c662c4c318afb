#include "cli/check_command.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "emulation/emulator_setup.hpp"
#include "exit_codes/exit_codes.hpp"
#include "recipe/program.hpp"
#include "recipe/recipe_loader.hpp"

namespace cellctl::cli {
namespace {

int run_check(const GlobalOptions& global, const std::vector<std::string>& recipes) {
  // Problems go to stdout as plain "file:line:column: field: rule" lines, one per problem, so that
  // editors and CI can jump to them.
  config::CellConfig cell;
  try {
    cell = device_seam::load_cell_config(global.config);
    // The emulators' set-up too, loaded only to be checked: a dry run must not be the first to find a
    // bad emulator section.
    (void)emulation::load_emulator_setup(cell);
  } catch (const config::ConfigError& e) {
    fmt::print("{}\n", e.what());
    return kExitConfig;
  }
  int bad = 0;
  for (const auto& path : recipes) {
    try {
      const auto recipe = recipe::load_recipe(path, cell);
      const auto program = recipe::unroll(recipe);
      fmt::print("{}: ok — '{}' version {} for cell '{}', {} steps:\n", path, recipe.name, recipe.version,
                 recipe.cell, program.instructions.size());
      // Numbered as `cellctl run`, its journal and `cellctl report` number them.
      for (std::size_t i = 0; i < program.instructions.size(); ++i)
        fmt::print("  {:>3}  {}\n", i + 1, program.instructions[i].label);
    } catch (const recipe::RecipeErrors& e) {
      fmt::print("{}\n", e.what());
      fmt::print("{}: {} problem{}; nothing was moved\n", path, e.errors().size(),
                 e.errors().size() == 1 ? "" : "s");
      ++bad;
    } catch (const config::ConfigError& e) {
      // Not read at all: unreadable, not UTF-8 text, or not one well-formed YAML document.
      fmt::print("{}\n{}: 1 problem; nothing was moved\n", e.what(), path);
      ++bad;
    }
  }
  return bad == 0 ? kExitOk : kExitConfig;
}

}  // namespace

void add_check_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand("check", "Validate recipes against the cell config without moving anything");
  auto recipes = std::make_shared<std::vector<std::string>>();
  // No CLI::ExistingFile: a missing or unreadable recipe is bad input (exit 3, file:line:column and
  // the reason, from the loader), not a bad command line (exit 2).
  sub->add_option("recipes", *recipes, "Recipe files")->required();
  commands.on(sub, [&commands, recipes] { return run_check(commands.global, *recipes); });
}

}  // namespace cellctl::cli
