// The one YAML loader fed arbitrary text, as a cell config and as a recipe for the default cell.
// Properties: every input either loads or is refused with a config::ConfigError (a recipe: also
// RecipeErrors) that names the file and a position from line 1, column 1 on — never another
// exception, a crash or a hang; a recipe that loads unrolls within the stated instruction limit.

#include <string>

#include "config/cell_config.hpp"
#include "fuzz_input.hpp"
#include "recipe/program.hpp"
#include "recipe/recipe_loader.hpp"
#include "targets.hpp"

namespace cellctl::fuzz {
namespace {

constexpr const char* kLabel = "fuzz.yaml";

void check_refusal(const config::ConfigError& e) {
  FUZZ_CHECK(e.file() == kLabel);
  FUZZ_CHECK(e.line() >= 1);
  FUZZ_CHECK(e.column() >= 1);
  FUZZ_CHECK(!e.rule().empty());
}

std::string as_text(std::span<const std::uint8_t> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

const config::CellConfig& default_cell() {
  static const config::CellConfig cell = config::load_cell_config(CELLCTL_CELL_YAML);
  return cell;
}

}  // namespace

void yaml_config(std::span<const std::uint8_t> bytes) {
  try {
    (void)config::parse_cell_config(config::YamlNode::load_string(as_text(bytes), kLabel), kLabel);
  } catch (const config::ConfigError& e) {
    check_refusal(e);
  }
}

void yaml_recipe(std::span<const std::uint8_t> bytes) {
  const auto& cell = default_cell();
  try {
    const auto recipe = recipe::parse_recipe(config::YamlNode::load_string(as_text(bytes), kLabel), cell);
    const auto program = recipe::unroll(recipe);
    FUZZ_CHECK(!program.instructions.empty());
    FUZZ_CHECK(program.instructions.size() <= static_cast<std::size_t>(recipe::kMaxInstructions));
  } catch (const recipe::RecipeErrors& e) {
    FUZZ_CHECK(!e.errors().empty());
    for (const auto& error : e.errors()) check_refusal(error);
  } catch (const config::ConfigError& e) {
    check_refusal(e);
  }
}

}  // namespace cellctl::fuzz
