// The page's Start list: each recipe in the folder validated against the cell, with its steps and its
// planned time (a lower bound: dwells, and moves from their axes' previous targets at their speed), or
// why it cannot be started; what is no recipe, or too large, is not loaded.
#include "web/recipe_list.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "config/cell_config.hpp"

namespace cellctl::web {
namespace {

namespace fs = std::filesystem;

recipe::Step move(std::vector<recipe::AxisTarget> to, double speed) {
  return {"move", 0, recipe::Move{std::move(to), speed, recipe::Path::time}};
}
recipe::Step dwell(double s) {
  return {"dwell", 0, recipe::Dwell{s}};
}

TEST(RecipeList, PlannedTimeCountsDwellsAndMovesFromTheirPreviousTargets) {
  recipe::Recipe r;
  r.steps = {move({{0, 20.0}, {1, 10.0}}, 10.0),            // the first: its start is where the cell stands
             dwell(0.5), move({{0, 5.0}, {1, 5.0}}, 5.0)};  // 15 mm at 5 mm/s: 3 s
  EXPECT_DOUBLE_EQ(planned_at_least_s(r), 3.5);
  recipe::Recipe repeated;
  recipe::Repeat rep{3, {move({{0, 10.0}}, 10.0), move({{0, 0.0}}, 10.0)}};
  repeated.steps = {{"back and forth", 0, rep}};
  // 1 s back, then 1 s there and 1 s back twice more: the first move of all is not counted.
  EXPECT_DOUBLE_EQ(planned_at_least_s(repeated), 5.0);
}

class RecipeFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cellctl-recipe-list-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::copy_file(fs::path(CELLCTL_SOURCE_DIR) / "tests/cli/short.yaml", dir_ / "short.yaml");
    fs::copy_file(fs::path(CELLCTL_SOURCE_DIR) / "tests/cli/bad-recipe.yaml", dir_ / "bad.yaml");
    std::ofstream(dir_ / "notes.txt") << "no recipe\n";
    std::ofstream(dir_ / ".hidden.yaml") << "recipe: {}\n";
    std::ofstream(dir_ / "huge.yaml") << std::string(kMaxRecipeBytes + 1, '#');
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  // The whole config, as cellctl serve loads it (the SCU's resolution bounds a recipe's tolerances).
  const config::CellConfig cell_ =
      config::load_cell_config(fs::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml");
};

TEST_F(RecipeFolder, ListsEachRecipeByNameWithStepsAndPlannedTimeOrItsProblem) {
  const auto list = recipe_list(dir_, cell_);
  ASSERT_EQ(list["recipes"].size(), 3u) << list.dump();
  const auto& bad = list["recipes"][0];
  EXPECT_EQ(bad["name"], "bad");
  EXPECT_NE(bad.value("problem", "").find("250 is out of range"), std::string::npos) << bad;
  const auto& huge = list["recipes"][1];
  EXPECT_EQ(huge["name"], "huge");
  EXPECT_NE(huge.value("problem", "").find("larger than"), std::string::npos) << huge;
  const auto& short_recipe = list["recipes"][2];
  EXPECT_EQ(short_recipe["name"], "short");
  EXPECT_EQ(short_recipe["steps"], 6);
  EXPECT_DOUBLE_EQ(short_recipe["planned_s"].get<double>(), 1.6);  // 0.3 s dwell + 15 mm at 12 mm/s
  EXPECT_FALSE(list["more"].get<bool>());
}

TEST_F(RecipeFolder, AFolderThatIsNotThereListsNothing) {
  const auto list = recipe_list(dir_ / "missing", cell_);
  EXPECT_TRUE(list["recipes"].empty());
}

}  // namespace
}  // namespace cellctl::web
