#include "recipe/program.hpp"

#include <fmt/format.h>

#include <algorithm>

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

std::string_view job_of(const Program& program) noexcept {
  const auto teaches = [](const Instruction& i) { return std::holds_alternative<TeachIn>(i.action); };
  const auto homes = [](const Instruction& i) { return std::holds_alternative<Home>(i.action); };
  const auto& ins = program.instructions;
  if (std::any_of(ins.begin(), ins.end(), teaches)) return "teach-in";
  if (!ins.empty() && std::all_of(ins.begin(), ins.end(), homes)) return "homing";
  return "recipe";
}

Program unroll(const Recipe& recipe) {
  Program p;
  unroll_into(recipe.steps, "", p);
  return p;
}

}  // namespace cellctl::recipe
