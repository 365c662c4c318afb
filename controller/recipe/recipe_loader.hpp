#pragma once
// Loads a recipe file and validates all of it against the cell before anything moves: the header
// names this cell, the recipe's limits sit inside the cell's, every target inside the recipe's
// limits, speeds and frequencies in range, axes that exist. Every problem is reported (not just the
// first), each as "file:line:column: field: rule".

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/cell_core.hpp"
#include "config/yaml_node.hpp"
#include "recipe/recipe.hpp"

namespace cellctl::recipe {

class RecipeErrors : public std::runtime_error {
 public:
  explicit RecipeErrors(std::vector<config::ConfigError> errors);
  [[nodiscard]] const std::vector<config::ConfigError>& errors() const noexcept { return errors_; }

 private:
  std::vector<config::ConfigError> errors_;
};

// Throws RecipeErrors (one or more problems) or config::ConfigError (unreadable YAML).
[[nodiscard]] Recipe load_recipe(const std::filesystem::path& path, const config::CellCore& cell);
[[nodiscard]] Recipe parse_recipe(const config::YamlNode& root, const config::CellCore& cell);

// Upper bounds that keep a recipe's unrolled program small enough to build before the run: repeats
// nest at most 4 deep and run at most 10000 times each, and the whole recipe unrolls to at most
// 100000 instructions. Counts are checked as they are read, before any multiplication.
inline constexpr int kMaxRepeatDepth = 4;
inline constexpr int kMaxRepeatTimes = 10'000;
inline constexpr long kMaxInstructions = 100'000;

}  // namespace cellctl::recipe
