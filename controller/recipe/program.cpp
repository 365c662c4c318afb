#include "recipe/program.hpp"

#include <fmt/format.h>

namespace cellctl::recipe {
namespace {

void unroll_into(const std::vector<Step>& steps, const std::string& prefix, Program& out) {
  for (const auto& step : steps) {
    if (const auto* repeat = std::get_if<Repeat>(&step.action)) {
      for (int i = 1; i <= repeat->times; ++i)
        unroll_into(repeat->steps, fmt::format("{}{} {}/{} › ", prefix, step.name, i, repeat->times), out);
      continue;
    }
    Instruction ins;
    ins.label = fmt::format("{}{} (line {})", prefix, step.name, step.line);
    ins.line = step.line;
    std::visit(
        [&](const auto& a) {
          if constexpr (!std::is_same_v<std::decay_t<decltype(a)>, Repeat>) ins.action = a;
        },
        step.action);
    out.instructions.push_back(std::move(ins));
  }
}

}  // namespace

Program unroll(const Recipe& recipe) {
  Program p;
  unroll_into(recipe.steps, "", p);
  return p;
}

}  // namespace cellctl::recipe
