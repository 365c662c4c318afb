#pragma once
// The recipes folder as the page's Start list (GET /recipes): each `<name>.yaml`, validated against
// the cell as a start would be (plant_link::CommandDesk), with its steps (unrolled) and its planned
// time — or why it cannot be started. Read on a server thread when the page asks, never on the loop.
//
// The planned time is the planner's (motion/planned_time.hpp: each move's jerk-limited profile at the
// cell's limits and its settle, dwells, the spindle's run-ups where its ramps are known), handed over
// by the command line as a recipe::ProgramTimer (the page does not see the planner), from where the
// page last saw the axes stand; the steps only the run can time are counted apart (not_counted).
//
// Without a timer no planned time is claimed. The JSON is the schema's (schema/page_payloads.hpp).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>

#include "config/cell_core.hpp"
#include "recipe/planned_time.hpp"
#include "schema/page_payloads.hpp"

namespace cellctl::web {

// Only so many recipes are listed (by name), each at most so large: a folder is no input to trust.
inline constexpr std::size_t kMaxListedRecipes = 100;
inline constexpr std::uintmax_t kMaxRecipeBytes = 1u << 20;

// `start_mm`: where each of the cell's axes stands (nullopt: not known).
[[nodiscard]] schema::RecipeList recipe_list(const std::filesystem::path& folder,
                                             const config::CellCore& cell, const recipe::ProgramTimer& timer,
                                             std::span<const std::optional<double>> start_mm);

}  // namespace cellctl::web
