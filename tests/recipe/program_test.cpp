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

TEST(Program, SaysWhatItIsForAsThePlantCountsIt) {
  Recipe r;
  r.steps = {Step{"home x", 3, Home{{0}}}, Step{"home z", 4, Home{{1}}}};
  EXPECT_EQ(job_of(unroll(r)), "homing");
  r.steps.push_back(Step{"go", 5, Move{{{0, 30.0}}, 15.0}});
  EXPECT_EQ(job_of(unroll(r)), "recipe") << "a recipe that homes first still produces";
  r.steps = {Step{"teach", 3, TeachIn{}}};
  EXPECT_EQ(job_of(unroll(r)), "teach-in");
  EXPECT_EQ(job_of(Program{}), "recipe");
}

}  // namespace
}  // namespace cellctl::recipe
