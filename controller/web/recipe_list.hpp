#pragma once
// The recipes folder as the page's Start list (GET /recipes): each `<name>.yaml`, validated against
// the cell as a start would be (plant_link::CommandDesk), with its steps (unrolled) and its planned
// time — or why it cannot be started. Read on a server thread when the page asks, never on the loop.
//
// The planned time is a lower bound: each dwell's seconds and each move's travel at its speed (from
// the previous target of its axes); ramps, spindle run-ups, waits and each axis's first move (it
// starts where the cell stands) are not known before the run and not counted.
//
// {"recipes":[{"name":"demo","steps":12,"planned_s":34.5},{"name":"bad","problem":"…"}],"more":false}

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "config/cell_core.hpp"
#include "recipe/recipe.hpp"

namespace cellctl::web {

// Only so many recipes are listed (by name), each at most so large: a folder is no input to trust.
inline constexpr std::size_t kMaxListedRecipes = 100;
inline constexpr std::uintmax_t kMaxRecipeBytes = 1u << 20;

// The lower bound above, in seconds.
[[nodiscard]] double planned_at_least_s(const recipe::Recipe& recipe);

[[nodiscard]] nlohmann::json recipe_list(const std::filesystem::path& folder, const config::CellCore& cell);

}  // namespace cellctl::web
