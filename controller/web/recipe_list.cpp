#include "web/recipe_list.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

#include "recipe/program.hpp"
#include "recipe/recipe_loader.hpp"

namespace cellctl::web {
namespace {

// The first problem's words (a recipe with several says how many more).
std::string problem_of(const recipe::RecipeErrors& e) {
  const auto& errors = e.errors();
  if (errors.empty()) return e.what();
  return fmt::format("{}{}", errors.front().what(),
                     errors.size() > 1 ? fmt::format(" (and {} more)", errors.size() - 1) : "");
}

}  // namespace

schema::RecipeList recipe_list(const std::filesystem::path& folder, const config::CellCore& cell,
                               const recipe::ProgramTimer& timer,
                               std::span<const std::optional<double>> start_mm) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const auto& p = entry.path();
    if (p.extension() == ".yaml" && !p.stem().empty() && p.stem().string().front() != '.' &&
        entry.is_regular_file(ec))
      files.push_back(p);
  }
  std::sort(files.begin(), files.end());
  schema::RecipeList list;
  for (std::size_t i = 0; i < files.size() && i < kMaxListedRecipes; ++i) {
    schema::RecipeEntry r;
    r.name = files[i].stem().string();
    try {
      if (std::filesystem::file_size(files[i]) > kMaxRecipeBytes)
        throw std::runtime_error(fmt::format("larger than {} bytes", kMaxRecipeBytes));
      const auto loaded = recipe::load_recipe(files[i], cell);
      const auto program = recipe::unroll(loaded);
      r.steps = program.instructions.size();
      if (timer) {
        const auto planned = timer(program, start_mm);
        r.planned_s = std::round(planned.seconds * 10.0) / 10.0;
        r.not_counted = planned.not_counted;
      }
    } catch (const recipe::RecipeErrors& e) {
      r.problem = problem_of(e);
    } catch (const std::exception& e) {
      r.problem = e.what();
    }
    list.recipes.push_back(std::move(r));
  }
  list.more = files.size() > kMaxListedRecipes;
  return list;
}

}  // namespace cellctl::web
