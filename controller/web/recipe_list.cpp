#include "web/recipe_list.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include "recipe/program.hpp"
#include "recipe/recipe_loader.hpp"

namespace cellctl::web {
namespace {

// Where each axis was last sent, as the steps go by: a move's travel is known from there.
using LastTargets = std::map<int, double>;

double steps_at_least_s(const std::vector<recipe::Step>& steps, LastTargets& last);

double step_at_least_s(const recipe::Step& step, LastTargets& last) {
  if (const auto* d = std::get_if<recipe::Dwell>(&step.action)) return d->seconds;
  if (const auto* m = std::get_if<recipe::Move>(&step.action)) {
    double travel = 0.0;
    for (const auto& t : m->targets) {
      if (const auto it = last.find(t.axis); it != last.end())
        travel = std::max(travel, std::abs(t.target_mm - it->second));
      last[t.axis] = t.target_mm;
    }
    return m->speed_mm_s > 0.0 ? travel / m->speed_mm_s : 0.0;
  }
  if (const auto* r = std::get_if<recipe::Repeat>(&step.action)) {
    double total = 0.0;
    for (int i = 0; i < r->times; ++i) total += steps_at_least_s(r->steps, last);
    return total;
  }
  return 0.0;
}

double steps_at_least_s(const std::vector<recipe::Step>& steps, LastTargets& last) {
  double total = 0.0;
  for (const auto& s : steps) total += step_at_least_s(s, last);
  return total;
}

// The first problem's words (a recipe with several says how many more).
std::string problem_of(const recipe::RecipeErrors& e) {
  const auto& errors = e.errors();
  if (errors.empty()) return e.what();
  return fmt::format("{}{}", errors.front().what(),
                     errors.size() > 1 ? fmt::format(" (and {} more)", errors.size() - 1) : "");
}

}  // namespace

double planned_at_least_s(const recipe::Recipe& recipe) {
  LastTargets last;
  return steps_at_least_s(recipe.steps, last);
}

nlohmann::json recipe_list(const std::filesystem::path& folder, const config::CellCore& cell) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const auto& p = entry.path();
    if (p.extension() == ".yaml" && !p.stem().empty() && p.stem().string().front() != '.' &&
        entry.is_regular_file(ec))
      files.push_back(p);
  }
  std::sort(files.begin(), files.end());
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < files.size() && i < kMaxListedRecipes; ++i) {
    nlohmann::json r{{"name", files[i].stem().string()}};
    try {
      if (std::filesystem::file_size(files[i]) > kMaxRecipeBytes)
        throw std::runtime_error(fmt::format("larger than {} bytes", kMaxRecipeBytes));
      const auto loaded = recipe::load_recipe(files[i], cell);
      r["steps"] = recipe::unroll(loaded).instructions.size();
      r["planned_s"] = std::round(planned_at_least_s(loaded) * 10.0) / 10.0;
    } catch (const recipe::RecipeErrors& e) {
      r["problem"] = problem_of(e);
    } catch (const std::exception& e) {
      r["problem"] = e.what();
    }
    list.push_back(std::move(r));
  }
  return {{"recipes", std::move(list)}, {"more", files.size() > kMaxListedRecipes}};
}

}  // namespace cellctl::web
