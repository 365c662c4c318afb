#include "jobs/home_job.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "recipe/recipe_loader.hpp"

namespace cellctl::jobs {

std::variant<std::vector<std::size_t>, std::string> homing_axes(const config::CellConfig& cell,
                                                                const std::filesystem::path& config_file,
                                                                const std::vector<std::string>& names) {
  std::vector<std::size_t> axes;
  for (const auto& name : names) {
    const auto* a = cell.axis(name);
    if (!a) return fmt::format("the cell has no axis '{}'", name);
    if (a->homing.strategy == config::HomingStrategy::none)
      return fmt::format("axis {} has no homing in {} (axes[].homing.strategy)", name, config_file.string());
    const auto i = static_cast<std::size_t>(a - cell.axes.data());
    if (std::find(axes.begin(), axes.end(), i) == axes.end()) axes.push_back(i);
  }
  if (names.empty())
    for (std::size_t i = 0; i < cell.axes.size(); ++i)
      if (cell.axes[i].homing.strategy != config::HomingStrategy::none) axes.push_back(i);
  if (axes.empty())
    return fmt::format("no axis in {} has homing (axes[].homing.strategy)", config_file.string());
  std::stable_sort(axes.begin(), axes.end(), [&](std::size_t l, std::size_t r) {
    return cell.axes[l].homing.sequence < cell.axes[r].homing.sequence;
  });
  return axes;
}

recipe::Recipe write_homing_recipe(const config::CellConfig& cell, const std::vector<std::size_t>& axes,
                                   const std::filesystem::path& run_dir) {
  std::vector<std::string> names;
  for (const auto i : axes) names.push_back(cell.axes[i].name);
  std::filesystem::create_directories(run_dir);
  const auto file = run_dir / "home.yaml";
  {
    std::ofstream out(file);
    out << fmt::format(
        "# Written by cellctl: the homing this run record is of.\n"
        "recipe: {{name: home, version: \"1\", cell: {}, description: \"home {}\"}}\n"
        "limits: {{axes: {{}}}}\n"
        "steps:\n"
        "  - name: home {}\n"
        "    home: [{}]\n",
        cell.name, fmt::join(names, " "), fmt::join(names, ", "), fmt::join(names, ", "));
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", file.string()));
  }
  return recipe::load_recipe(file, cell);
}

}  // namespace cellctl::jobs
