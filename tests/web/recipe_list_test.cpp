// The page's Start list: each recipe in the folder validated against the cell, with its steps and the
// planned time its timer gives (the planner's, handed over by the command line: tested against runs in
// tests/integration/planned_time_test.cpp) from where the axes stand, or why it cannot be started;
// what is no recipe, or too large, is not loaded.
#include "web/recipe_list.hpp"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "config/cell_config.hpp"

namespace cellctl::web {
namespace {

namespace fs = std::filesystem;

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
  // A timer that says what it was given: the program's steps and the start of x.
  std::vector<std::optional<double>> seen_start;
  const recipe::ProgramTimer timer = [&](const recipe::Program& p,
                                         std::span<const std::optional<double>> start) {
    seen_start.assign(start.begin(), start.end());
    return recipe::PlannedTime{static_cast<double>(p.instructions.size()) + 0.04, 2};
  };
  const std::array<std::optional<double>, 2> start{12.5, std::nullopt};
  const auto typed = recipe_list(dir_, cell_, timer, start);
  // As the page sends it: the same bytes as before its JSON moved into the schema.
  EXPECT_EQ(
      schema::recipe_list_json(typed),
      R"({"more":false,"recipes":[{"name":"bad","problem":")" + (dir_ / "bad.yaml").string() +
          R"(:13:15: steps[0].move.to.x: 250 is out of range [0, 180]"},{"name":"huge","problem":"larger )"
          R"(than 1048576 bytes"},{"name":"short","not_counted":2,"planned_s":6.0,"steps":6}]})");
  const auto list = nlohmann::json::parse(schema::recipe_list_json(typed));
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
  EXPECT_DOUBLE_EQ(short_recipe["planned_s"].get<double>(), 6.0);  // to the tenth of a second
  EXPECT_EQ(short_recipe["not_counted"], 2);
  ASSERT_EQ(seen_start.size(), 2u);
  EXPECT_EQ(seen_start[0], 12.5);
  EXPECT_FALSE(seen_start[1]);
  EXPECT_FALSE(list["more"].get<bool>());
}

TEST_F(RecipeFolder, WithoutATimerNoPlannedTimeIsClaimed) {
  const auto list = nlohmann::json::parse(schema::recipe_list_json(recipe_list(dir_, cell_, {}, {})));
  const auto& short_recipe = list["recipes"][2];
  EXPECT_EQ(short_recipe["steps"], 6);
  EXPECT_FALSE(short_recipe.contains("planned_s")) << short_recipe;
  EXPECT_FALSE(short_recipe.contains("not_counted")) << short_recipe;
}

TEST_F(RecipeFolder, AFolderThatIsNotThereListsNothing) {
  const auto list =
      nlohmann::json::parse(schema::recipe_list_json(recipe_list(dir_ / "missing", cell_, {}, {})));
  EXPECT_TRUE(list["recipes"].empty());
}

}  // namespace
}  // namespace cellctl::web
