#pragma once
// A recipe unrolled into the flat list of actions the supervisor executes, one after the other:
// repeats expanded, each action labelled with where it came from ("3/12 repeat 2/5 › drill (line 31)").
// Built once before the run; the supervisor then only indexes into it (no allocation in the cycle).

#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "recipe/recipe.hpp"

namespace cellctl::recipe {

struct Instruction {
  std::string label;  // human-readable, for status, journal and summary
  int line = 0;
  std::variant<Move, Spindle, Dwell, Wait, Require, Home, TeachIn> action;
};

struct Program {
  std::vector<Instruction> instructions;
};

[[nodiscard]] Program unroll(const Recipe& recipe);

// What a program is for, as the plant counts it: "teach-in" when it teaches the encoder, "homing" when
// it does nothing but home, else "recipe" (production, homing steps or not).
[[nodiscard]] std::string_view job_of(const Program& program) noexcept;

}  // namespace cellctl::recipe
