#pragma once
// Homing as a job: which axes, in which order, and the one-step recipe (`home: [...]`) that homes
// them — what `cellctl home` runs and what `cellctl serve` runs when the plant or the page asks.

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "config/cell_config.hpp"
#include "recipe/recipe.hpp"

namespace cellctl::jobs {

// The axes to home in the order of homing.sequence: the named ones (each must exist and have homing)
// or, none named, every axis that has homing. The indexes into cell.axes, or why not.
[[nodiscard]] std::variant<std::vector<std::size_t>, std::string> homing_axes(
    const config::CellConfig& cell, const std::filesystem::path& config_file,
    const std::vector<std::string>& names);

// Writes the one-step recipe that homes `axes` into `run_dir`/home.yaml (kept with the run record:
// `cellctl run <dir>/home.yaml` does the same again) and loads it. Throws std::runtime_error when
// the file cannot be written, recipe::RecipeErrors when it does not load.
[[nodiscard]] recipe::Recipe write_homing_recipe(const config::CellConfig& cell,
                                                 const std::vector<std::size_t>& axes,
                                                 const std::filesystem::path& run_dir);

}  // namespace cellctl::jobs
