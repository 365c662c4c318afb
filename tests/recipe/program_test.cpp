#include "recipe/program.hpp"

#include <gtest/gtest.h>

#include "recipe/recipe_loader.hpp"

namespace cellctl::recipe {
namespace {

TEST(Program, UnrollsRepeatsWithLabels) {
  Recipe r;
  Step dwell{"dwell at depth", 20, Dwell{0.5}};
  Step move{"peck in", 19, Move{{{1, 60.0}}, 6.0}};
  Repeat rep{2, {move, dwell}};
  r.steps = {Step{"go", 10, Move{{{0, 30.0}}, 15.0}}, Step{"drill", 17, rep},
             Step{"stop", 30, Spindle{false}}};
  const auto p = unroll(r);
  ASSERT_EQ(p.instructions.size(), 6u);
  EXPECT_EQ(p.instructions[0].label, "go (line 10)");
  EXPECT_EQ(p.instructions[1].label, "drill 1/2 › peck in (line 19)");
  EXPECT_EQ(p.instructions[4].label, "drill 2/2 › dwell at depth (line 20)");
  EXPECT_TRUE(std::holds_alternative<Spindle>(p.instructions[5].action));
  EXPECT_DOUBLE_EQ(std::get<Dwell>(p.instructions[4].action).seconds, 0.5);
}

}  // namespace
}  // namespace cellctl::recipe
