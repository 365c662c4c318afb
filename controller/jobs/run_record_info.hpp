#pragma once
// What `cellctl run` writes at the head of its run record and says in its banner: the recipe and
// config files, the mode and where each device is reached, the axes and the steps as numbered.

#include <filesystem>
#include <string>

#include "config/cell_config.hpp"
#include "journal/record_header.hpp"
#include "recipe/program.hpp"
#include "recipe/recipe.hpp"
#include "runtime/cell_links.hpp"

namespace cellctl::jobs {

// "emulated (every device on its emulator, in this process)", "hardware", "hardware (spindle
// emulated in-process)", "virtual time": what the banner and the record say the run was.
[[nodiscard]] std::string mode_label(const config::CellConfig& cell, runtime::RunMode mode);

[[nodiscard]] journal::RecordInfo record_info(const config::CellConfig& cell,
                                              const std::filesystem::path& config_file,
                                              const recipe::Recipe& recipe, const recipe::Program& program,
                                              runtime::RunMode mode);

// runs/<recipe file's stem>-<local start time>, e.g. runs/demo-20261124-091502.
[[nodiscard]] std::filesystem::path default_run_dir(const std::filesystem::path& recipe_file);

}  // namespace cellctl::jobs
