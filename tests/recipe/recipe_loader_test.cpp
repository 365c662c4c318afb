// The recipe validator: valid recipes load, and every malformed or out-of-limit recipe is refused
// before any motion with the exact "file:line:column: field: rule" an operator needs to fix it.

#include "recipe/recipe_loader.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "config/cell_config.hpp"

namespace cellctl::recipe {
namespace {

using config::YamlNode;

config::CellConfig test_cell() {
  return config::parse_cell_config(YamlNode::load_string(R"(cell: test-cell
axes:
  - {name: x, actuator: 1, function: 1, edges_per_mm: 10, min_mm: 0, max_mm: 190, max_speed_mm_s: 20, min_speed_mm_s: 0.8,
     homing: {strategy: scu_initialised}}
  - {name: z, actuator: 2, function: 2, edges_per_mm: 10, min_mm: 0, max_mm: 140, max_speed_mm_s: 15,
     homing: {strategy: scu_initialised}}
limits: {spindle_min_hz: 100, spindle_max_hz: 800}
)",
                                                         "cell.yaml"),
                                   "cell.yaml");
}

const std::string kHeader = R"(recipe:
  name: t
  version: "1"
  cell: test-cell
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
    z: {min_mm: 0, max_mm: 120, max_speed_mm_s: 12, tolerance_mm: 0.1}
  spindle: {min_hz: 200, max_hz: 600}
steps:
)";  // steps start on line 11

Recipe load(const std::string& text) {
  return parse_recipe(YamlNode::load_string(text, "r.yaml"), test_cell());
}

std::vector<std::string> errors_of(const std::string& text) {
  try {
    (void)load(text);
  } catch (const RecipeErrors& e) {
    std::vector<std::string> out;
    for (const auto& err : e.errors()) out.emplace_back(err.what());
    return out;
  } catch (const config::ConfigError& e) {
    return {e.what()};
  }
  return {};
}

TEST(RecipeLoader, LoadsAValidRecipe) {
  const auto r = load(kHeader + R"(  - name: check
    require: {encoder_ready: true, homed: [x]}
  - move: {to: {x: 30, z: 20}, speed_mm_s: 10}
  - spindle: {start_hz: 400, direction: ccw}
  - repeat:
      times: 3
      steps:
        - {name: in, move: {to: {z: 60}, speed_mm_s: 5}}
        - dwell: 0.5
  - wait: {axis: x, position_above_mm: 10, timeout_s: 2}
  - wait: {spindle: at_rest, timeout_s: 2}
  - spindle: stop
)");
  EXPECT_EQ(r.name, "t");
  ASSERT_EQ(r.steps.size(), 7u);
  EXPECT_EQ(r.steps[0].name, "check");
  EXPECT_EQ(r.steps[1].name, "move");
  EXPECT_EQ(r.steps[1].line, 13);
  const auto& move = std::get<Move>(r.steps[1].action);
  ASSERT_EQ(move.targets.size(), 2u);
  EXPECT_EQ(move.targets[1].axis, 1);
  EXPECT_DOUBLE_EQ(move.targets[1].target_mm, 20.0);
  EXPECT_EQ(std::get<Spindle>(r.steps[2].action).direction, SpindleDirection::ccw);
  EXPECT_EQ(std::get<Repeat>(r.steps[3].action).times, 3);
  EXPECT_FALSE(std::get<Spindle>(r.steps[6].action).start);
  EXPECT_DOUBLE_EQ(r.limits.axes[0]->tolerance_mm, 0.1);
}

TEST(RecipeLoader, ShippedRecipesLoadAgainstTheDefaultCell) {
  const auto cell = config::load_cell_config(std::string(CELLCTL_SOURCE_DIR) + "/config/cell.yaml");
  const auto r = load_recipe(std::string(CELLCTL_SOURCE_DIR) + "/recipes/demo.yaml", cell);
  EXPECT_EQ(r.name, "demo-drilling");
}

struct BadCase {
  const char* what;
  std::string text;
  std::string message;  // the first (or only) error, exactly
};

void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.what;
}

class RecipeRejects : public ::testing::TestWithParam<BadCase> {};

TEST_P(RecipeRejects, WithTheExactMessage) {
  const auto& c = GetParam();
  const auto errors = errors_of(c.text);
  ASSERT_FALSE(errors.empty()) << c.what << ": accepted";
  EXPECT_EQ(errors.front(), c.message) << c.what;
}

std::string with_steps(const std::string& steps) {
  return kHeader + steps;
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, RecipeRejects,
    ::testing::Values(
        BadCase{"not YAML", "recipe: [\n", "r.yaml:2:1: invalid YAML: end of sequence flow not found"},
        BadCase{"no header", "limits: {axes: {}}\nsteps: [{dwell: 1}]\n",
                "r.yaml:1:1: missing required field 'recipe'"},
        BadCase{"wrong cell", R"(recipe: {name: t, version: "1", cell: other}
limits: {axes: {}}
steps: [{dwell: 1}]
)",
                "r.yaml:1:39: recipe.cell: the recipe is for cell 'other', but this cell is 'test-cell' "
                "(cell.yaml)"},
        BadCase{
            "empty name",
            "recipe: {name: '', version: '1', cell: test-cell}\nlimits: {axes: {}}\nsteps: [{dwell: 1}]\n",
            "r.yaml:1:16: recipe.name: must not be empty"},
        BadCase{"unknown top-level key", kHeader + "  - dwell: 1\nstep_list: []\n",
                "r.yaml:12:1: step_list: unknown field"},
        BadCase{"misspelt header key", R"(recipe: {name: t, versoin: "1", cell: test-cell}
limits: {axes: {}}
steps: [{dwell: 1}]
)",
                "r.yaml:1:19: recipe.versoin: unknown field (did you mean 'version'?)"},
        BadCase{"unknown axis in limits", R"(recipe: {name: t, version: "1", cell: test-cell}
limits:
  axes:
    y: {min_mm: 0, max_mm: 10, max_speed_mm_s: 5, tolerance_mm: 0.1}
steps: [{dwell: 1}]
)",
                "r.yaml:4:8: limits.axes.y: the cell has no axis 'y' (its axes: x, z)"},
        BadCase{"recipe limit outside the cell", R"(recipe: {name: t, version: "1", cell: test-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 250, max_speed_mm_s: 5, tolerance_mm: 0.1}
steps: [{dwell: 1}]
)",
                "r.yaml:4:28: limits.axes.x.max_mm: 250 is out of range [0, 190]"},
        BadCase{"max below min", R"(recipe: {name: t, version: "1", cell: test-cell}
limits:
  axes:
    x: {min_mm: 50, max_mm: 40, max_speed_mm_s: 5, tolerance_mm: 0.1}
steps: [{dwell: 1}]
)",
                "r.yaml:4:29: limits.axes.x.max_mm: must be above min_mm (50)"},
        BadCase{"speed limit above the cell's", R"(recipe: {name: t, version: "1", cell: test-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 40, max_speed_mm_s: 50, tolerance_mm: 0.1}
steps: [{dwell: 1}]
)",
                "r.yaml:4:48: limits.axes.x.max_speed_mm_s: 50 is out of range [0.8, 20]"},
        BadCase{"tolerance finer than one edge", R"(recipe: {name: t, version: "1", cell: test-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 40, max_speed_mm_s: 5, tolerance_mm: 0.01}
steps: [{dwell: 1}]
)",
                "r.yaml:4:65: limits.axes.x.tolerance_mm: 0.01 is out of range [0.1, 5]"},
        BadCase{"spindle limits outside the cell", R"(recipe: {name: t, version: "1", cell: test-cell}
limits:
  axes: {}
  spindle: {min_hz: 50, max_hz: 600}
steps: [{dwell: 1}]
)",
                "r.yaml:4:21: limits.spindle.min_hz: 50 is out of range [100, 800]"},
        BadCase{"no steps", kHeader + "  []\n", "r.yaml:11:3: steps: a recipe needs at least one step"},
        BadCase{"empty steps", R"(recipe: {name: t, version: "1", cell: test-cell}
limits: {axes: {}}
steps: []
)",
                "r.yaml:3:8: steps: a recipe needs at least one step"},
        BadCase{"unknown action", with_steps("  - drill: {depth: 5}\n"),
                "r.yaml:11:5: steps[0].drill: unknown field (did you mean 'dwell'?)"},
        BadCase{"two actions in one step", with_steps("  - {dwell: 1, move: {to: {x: 1}, speed_mm_s: 5}}\n"),
                "r.yaml:11:5: steps[0]: a step does one thing: both 'move' and 'dwell' given"},
        BadCase{"target outside recipe limits", with_steps("  - move: {to: {x: 185}, speed_mm_s: 10}\n"),
                "r.yaml:11:20: steps[0].move.to.x: 185 is out of range [0, 180]"},
        BadCase{"move of an axis that does not exist", with_steps("  - move: {to: {q: 5}, speed_mm_s: 10}\n"),
                "r.yaml:11:20: steps[0].move.to.q: the cell has no axis 'q' (its axes: x, z)"},
        BadCase{"speed above the recipe limit", with_steps("  - move: {to: {z: 5}, speed_mm_s: 14}\n"),
                "r.yaml:11:36: steps[0].move.speed_mm_s: 14 mm/s is above axis 'z''s recipe limit 12 mm/s"},
        BadCase{"speed too low to move", with_steps("  - move: {to: {x: 5}, speed_mm_s: 0.3}\n"),
                "r.yaml:11:36: steps[0].move.speed_mm_s: 0.3 mm/s is below axis 'x''s minimum 0.8 mm/s: the "
                "actuator "
                "would not move"},
        BadCase{"zero speed on an axis without a minimum",
                with_steps("  - move: {to: {z: 5}, speed_mm_s: 0}\n"),
                "r.yaml:11:36: steps[0].move.speed_mm_s: 0 mm/s: a move needs a speed above 0 mm/s"},
        BadCase{"negative speed", with_steps("  - move: {to: {z: 5}, speed_mm_s: -4}\n"),
                "r.yaml:11:36: steps[0].move.speed_mm_s: -4 mm/s: a move needs a speed above 0 mm/s"},
        BadCase{"move without a target", with_steps("  - move: {to: {}, speed_mm_s: 5}\n"),
                "r.yaml:11:16: steps[0].move.to: name at least one axis and its target"},
        BadCase{"move without a speed", with_steps("  - move: {to: {x: 5}}\n"),
                "r.yaml:11:11: steps[0].move: missing required field 'speed_mm_s'"},
        BadCase{"text where a number belongs", with_steps("  - move: {to: {x: five}, speed_mm_s: 5}\n"),
                "r.yaml:11:20: steps[0].move.to.x: expected a number, got 'five'"},
        BadCase{"spindle frequency out of range", with_steps("  - spindle: {start_hz: 700}\n"),
                "r.yaml:11:25: steps[0].spindle.start_hz: 700 is out of range [200, 600]"},
        BadCase{"spindle direction", with_steps("  - spindle: {start_hz: 400, direction: left}\n"),
                "r.yaml:11:41: steps[0].spindle.direction: 'left' is not one of: cw, ccw"},
        BadCase{"spindle word", with_steps("  - spindle: halt\n"),
                "r.yaml:11:14: steps[0].spindle: 'halt' is not one of: stop"},
        BadCase{"negative dwell", with_steps("  - dwell: -1\n"),
                "r.yaml:11:12: steps[0].dwell: -1 is out of range [0.001, 3600]"},
        BadCase{"wait without a timeout", with_steps("  - wait: {encoder: ready}\n"),
                "r.yaml:11:11: steps[0].wait: missing required field 'timeout_s'"},
        BadCase{"wait with two conditions",
                with_steps("  - wait: {encoder: ready, spindle: at_speed, timeout_s: 1}\n"),
                "r.yaml:11:11: steps[0].wait: a wait needs exactly one condition: position_above_mm, "
                "position_below_mm, encoder or spindle"},
        BadCase{"wait threshold outside the axis",
                with_steps("  - wait: {axis: z, position_above_mm: 500, timeout_s: 1}\n"),
                "r.yaml:11:40: steps[0].wait.position_above_mm: 500 is out of range [0, 140]"},
        BadCase{"repeat zero times", with_steps("  - repeat: {times: 0, steps: [{dwell: 1}]}\n"),
                "r.yaml:11:21: steps[0].repeat.times: 0 is out of range [1, 10000]"},
        BadCase{"repeat with no steps", with_steps("  - repeat: {times: 2, steps: []}\n"),
                "r.yaml:11:31: steps[0].repeat.steps: a repeat needs at least one step"},
        BadCase{"require of an unknown axis", with_steps("  - require: {homed: [x, w]}\n"),
                "r.yaml:11:26: steps[0].require.homed[1]: the cell has no axis 'w' (its axes: x, z)"},
        BadCase{"empty require", with_steps("  - require: {}\n"),
                "r.yaml:11:14: steps[0].require: require needs at least one of: homed, encoder_ready, "
                "spindle_at_rest"},
        BadCase{"a step that is not a mapping", with_steps("  - dwell 5\n"),
                "r.yaml:11:5: steps[0]: a step is a mapping with one of: move, spindle, dwell, wait, repeat, "
                "require, home"}));

TEST(RecipeLoader, ReportsEveryBadStepNotJustTheFirst) {
  const auto errors = errors_of(with_steps(R"(  - move: {to: {x: 185}, speed_mm_s: 10}
  - dwell: 1
  - dwell: 0
  - spindle: {start_hz: 900}
)"));
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_NE(errors[0].find("r.yaml:11:"), std::string::npos);
  EXPECT_NE(errors[1].find("r.yaml:13:"), std::string::npos);
  EXPECT_NE(errors[2].find("r.yaml:14:"), std::string::npos);
}

TEST(RecipeLoader, AMoveIsTimeSynchronisedUnlessItAsksForALine) {
  const auto r = load(with_steps(R"(  - move: {to: {x: 30, z: 20}, speed_mm_s: 10}
  - move: {to: {x: 40, z: 10}, speed_mm_s: 10, path: time}
  - move: {to: {x: 50, z: 30}, speed_mm_s: 10, path: line}
)"));
  ASSERT_EQ(r.steps.size(), 3u);
  EXPECT_EQ(std::get<Move>(r.steps[0].action).path, Path::time);
  EXPECT_EQ(std::get<Move>(r.steps[1].action).path, Path::time);
  EXPECT_EQ(std::get<Move>(r.steps[2].action).path, Path::line);
  const auto errors = errors_of(with_steps("  - move: {to: {x: 30}, speed_mm_s: 10, path: straight}\n"));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "r.yaml:11:47: steps[0].move.path: 'straight' is not one of: time, line");
}

TEST(RecipeLoader, AnAxisWithoutRecipeLimitsMayNotMove) {
  const auto errors = errors_of(R"(recipe: {name: t, version: "1", cell: test-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 40, max_speed_mm_s: 5, tolerance_mm: 0.1}
steps:
  - move: {to: {z: 5}, speed_mm_s: 1}
)");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0],
            "r.yaml:6:20: steps[0].move.to.z: axis 'z' has no limits in this recipe (limits.axes.z)");
}

TEST(RecipeLoader, SpindleStartNeedsSpindleLimits) {
  const auto errors = errors_of(R"(recipe: {name: t, version: "1", cell: test-cell}
limits: {axes: {}}
steps:
  - spindle: {start_hz: 300}
)");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0],
            "r.yaml:4:14: steps[0].spindle: the recipe starts the spindle but has no limits.spindle (min_hz, "
            "max_hz)");
}

TEST(RecipeLoader, RepeatsAreBoundedInDepthAndSize) {
  const auto deep =
      errors_of(with_steps("  - repeat: {times: 2, steps: [{repeat: {times: 2, steps: [{repeat: {times: 2, "
                           "steps: [{repeat: {times: 2, "
                           "steps: [{repeat: {times: 2, steps: [{dwell: 1}]}}]}}]}}]}}]}\n"));
  ASSERT_FALSE(deep.empty());
  EXPECT_NE(deep[0].find("repeats nest at most 4 deep"), std::string::npos) << deep[0];
  const auto big = errors_of(
      with_steps("  - repeat: {times: 10000, steps: [{repeat: {times: 10000, steps: [{dwell: 1}]}}]}\n"));
  ASSERT_EQ(big.size(), 1u);
  EXPECT_EQ(big[0],
            "r.yaml:11:53: steps[0].repeat.steps[0].repeat.times: 10000 times inside repeats that run 10000 "
            "times unrolls to more than 100000 steps (the limit)");
}

// The limit is exact: 10000 × 10 steps load, one more step is refused where the count passes it.
TEST(RecipeLoader, TheInstructionLimitIsExact) {
  std::string ten;
  for (int i = 0; i < 10; ++i) ten += "{dwell: 1}, ";
  const auto at_limit = load(with_steps("  - repeat: {times: 10000, steps: [" + ten + "]}\n"));
  EXPECT_EQ(std::get<Repeat>(at_limit.steps[0].action).steps.size(), 10u);
  const auto over = errors_of(with_steps("  - repeat: {times: 10000, steps: [" + ten + "]}\n  - dwell: 1\n"));
  ASSERT_EQ(over.size(), 1u);
  EXPECT_EQ(over[0], "r.yaml:12:5: steps[1]: the recipe unrolls to more than 100000 steps here (the limit)");
}

// UBSan found the product of nested counts overflowing before it was compared: four levels of
// 10000 times 1000 steps. Refused at the first count that passes the limit, nothing multiplied.
TEST(RecipeLoader, HugeNestedCountsAreRefusedBeforeTheyAreMultiplied) {
  const auto errors = errors_of(with_steps(
      "  - repeat: {times: 10000, steps: [{repeat: {times: 10000, steps: [{repeat: {times: 10000, steps: "
      "[{repeat: {times: 10000, steps: [{dwell: 1}]}}]}}]}}]}\n"));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("10000 times inside repeats that run 10000 times"), std::string::npos)
      << errors[0];
  const auto huge =
      errors_of(with_steps("  - repeat: {times: 99999999999999999999999, steps: [{dwell: 1}]}\n"));
  ASSERT_EQ(huge.size(), 1u);
  EXPECT_EQ(huge[0],
            "r.yaml:11:21: steps[0].repeat.times: 99999999999999999999999 is out of range [1, 10000]");
}

// A list of steps reused through aliases costs at most the limit's work, then the parse stops.
TEST(RecipeLoader, AliasedStepListsAreCountedEveryTimeTheyAreUsed) {
  std::string text = kHeader + "  - repeat:\n      times: 1\n      steps: &s0 [";
  for (int i = 0; i < 100; ++i) text += "{dwell: 1},";
  text += "]\n";
  for (int level = 1; level <= 3; ++level) {
    text += fmt::format("  - repeat:\n      times: 1\n      steps: &s{} [", level);
    for (int i = 0; i < 100; ++i) text += fmt::format("{{repeat: {{times: 1, steps: *s{}}}}},", level - 1);
    text += "]\n";
  }
  const auto errors = errors_of(text);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("100000 steps"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("(the limit)"), std::string::npos) << errors[0];
}

// yaml-cpp keeps one of two equal keys silently; the recipe would move to a target nobody checked.
TEST(RecipeLoader, ADuplicateKeyIsRefusedNamingBothPlaces) {
  const auto errors =
      errors_of(with_steps("  - move:\n      to: {x: 30}\n      speed_mm_s: 5\n      to: {x: 150}\n"));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(
      errors[0],
      "r.yaml:14:7: steps[0].move.to: duplicate key 'to': also given at line 12, column 7; which one is "
      "meant?");
}

}  // namespace
}  // namespace cellctl::recipe
